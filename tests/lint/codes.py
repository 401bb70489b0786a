#!/usr/bin/env python3
"""Every error and warning code the source can send is in the OpenAPI
template's enums (Error.code, Warning.code), and every code there is sent.

    codes.py SOURCE_DIR

Error codes: core's table (RD_ERRNO_MAP in core/include/rd_error.h, all but
"ok"), the server's own (the code argument of rd_http_send_server_error and
rd_http_error_response, and "code", "..." in a JSON body it writes).
Warning codes: api/rd_warnings.c's table and warn() calls, and "code", "..."
in a warning an analysis writes (api/rd_an_*.c).  Read off the source text:
a code built at run time would escape this check (none is today), which is
why tests/http/contract.py also validates the answers themselves."""
import glob
import json
import os
import re
import sys


def read(paths):
    """The files' text without their comments."""
    text = "\n".join(open(p, encoding="utf-8").read() for p in paths)
    return re.sub(r"/\*.*?\*/", " ", text, flags=re.S)


def main():
    if len(sys.argv) != 2:
        sys.exit("usage: codes.py SOURCE_DIR")
    root = sys.argv[1]
    errmap = read([os.path.join(root, "core/include/rd_error.h")])
    errors = set(re.findall(r'X\(\w+,\s*-?\d+,\s*"([a-z_]+)"', errmap)) - {"ok"}
    server = read(sorted(glob.glob(os.path.join(root, "server/*.c"))))
    errors |= set(re.findall(
        r'rd_http_send_server_error\(\s*\w+,\s*\w+,\s*\w+,\s*\w+,\s*"([a-z_]+)"', server))
    errors |= set(re.findall(r'rd_http_error_response\(\s*\w+,\s*"([a-z_]+)"', server))
    errors |= set(re.findall(r'"code",\s*"([a-z_]+)"', server))
    warn_src = read([os.path.join(root, "api/rd_warnings.c")])
    warnings = set(re.findall(r'\{"([a-z_]+)",\s*"/', warn_src))
    warnings |= set(re.findall(r'warn\(\s*\w+,\s*"([a-z_]+)"', warn_src))
    analyses = read(sorted(glob.glob(os.path.join(root, "api/rd_an_*.c"))))
    warnings |= set(re.findall(r'"code",\s*"([a-z_]+)"', analyses))
    if len(errors) < 15 or len(warnings) < 5:
        sys.exit("codes lint FAILED: found only %d error and %d warning codes in %s; "
                 "has the source moved?" % (len(errors), len(warnings), root))

    doc = json.load(open(os.path.join(root, "server/openapi.json"), encoding="utf-8"))
    schemas = doc["components"]["schemas"]
    failed = 0
    for name, found in (("Error", errors), ("Warning", warnings)):
        enum = set(schemas[name]["properties"]["code"]["enum"])
        for code in sorted(found - enum):
            print("FAIL - %s code %r is sent but not in %s.code's enum" % (name, code, name))
            failed += 1
        for code in sorted(enum - found):
            print("FAIL - %s.code lists %r, which nothing sends" % (name, code))
            failed += 1
        if not found - enum and not enum - found:
            print("ok   - %s.code lists the %d codes the source sends: %s" %
                  (name, len(found), ", ".join(sorted(found))))
    sys.exit(1 if failed else 0)


if __name__ == "__main__":
    main()
