# ringdyn-server on Debian bookworm, built exactly as scripts/run.sh builds it
# (Release, no tests, no benchmarks).
#
#   docker build -t ringdyn .
#   docker run --rm -p 127.0.0.1:8080:8080 ringdyn
#   curl http://127.0.0.1:8080/api/v1/health
#
# Inside the container the server must listen on all interfaces (0.0.0.0) for
# the published port to reach it, so it requires its access token (below);
# choose who can reach it with `docker run -p`.
FROM debian:bookworm

WORKDIR /app

# Dependencies first, in their own layer: rebuilt only when the script changes.
COPY scripts/install-deps.sh scripts/install-deps.sh
RUN scripts/install-deps.sh && rm -rf /var/lib/apt/lists/*

COPY . .
# A build/ directory copied from the host would carry a foreign CMakeCache.
RUN rm -rf build \
 && cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DRINGDYN_TESTS=OFF -DRINGDYN_BENCH=OFF \
 && cmake --build build -j"$(nproc)" \
 && install -m 0755 build/server/ringdyn-server /usr/local/bin/ringdyn-server \
 && install -m 0755 build/cli/ringdyn /usr/local/bin/ringdyn

# The server needs no privileges: it reads /app/static and /app/examples and
# writes only /data (the access token it makes on first start, and the job store).
RUN useradd --system --no-create-home --shell /usr/sbin/nologin ringdyn \
 && mkdir /data && chown ringdyn /data
USER ringdyn
VOLUME /data

# Listening on 0.0.0.0 needs a token: the first start writes a random one to
# /data/token (read it with `docker exec CONTAINER cat /data/token`, open the
# page once as http://127.0.0.1:8080/?token=TOKEN).  The health check needs none.
EXPOSE 8080
HEALTHCHECK --interval=30s --timeout=5s --start-period=5s \
  CMD curl -fsS http://127.0.0.1:8080/api/v1/health >/dev/null || exit 1
CMD ["sh", "-c", "[ -s /data/token ] || (umask 077 && head -c 24 /dev/urandom | base64 >/data/token) && exec ringdyn-server --host 0.0.0.0 --port 8080 --static /app/static --examples /app/examples --token-file /data/token --data /data"]
