# cmake -DIN=openapi.json -DOUT=rd_openapi_doc.c -DVERSION=x.y.z -P embed.cmake
# Writes IN as a NUL-terminated C byte array (rd_openapi_doc.h), with
# "@RINGDYN_VERSION@" replaced by VERSION.
file(READ "${IN}" text)
string(REPLACE "@RINGDYN_VERSION@" "${VERSION}" text "${text}")
file(WRITE "${OUT}.tmp" "${text}")
file(READ "${OUT}.tmp" hex HEX)
file(REMOVE "${OUT}.tmp")
string(REGEX REPLACE "([0-9a-f][0-9a-f][0-9a-f][0-9a-f][0-9a-f][0-9a-f][0-9a-f][0-9a-f][0-9a-f][0-9a-f][0-9a-f][0-9a-f][0-9a-f][0-9a-f][0-9a-f][0-9a-f][0-9a-f][0-9a-f][0-9a-f][0-9a-f][0-9a-f][0-9a-f][0-9a-f][0-9a-f])"
       "\\1\n" hex "${hex}")
string(REGEX REPLACE "([0-9a-f][0-9a-f])" "0x\\1," bytes "${hex}")
file(WRITE "${OUT}"
  "/* Generated from openapi.json by embed.cmake; do not edit. */\n"
  "#include \"rd_openapi_doc.h\"\n\n"
  "const char rd_openapi_json[] = {\n${bytes}0x00};\n"
  "const size_t rd_openapi_json_len = sizeof rd_openapi_json - 1;\n")
