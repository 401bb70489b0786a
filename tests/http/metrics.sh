#!/usr/bin/env bash
# GET /metrics by route and method (issue 44 item 5) against a live server:
# after a known set of requests, ringdyn_http_requests_total{route,method,
# status} grows by exactly their number under route templates (never a raw
# URL: unknown URLs land in "other"), the request-duration histogram by route
# counts the same requests, and job counts and run times carry the analysis.
#   metrics.sh SERVER JQ STATIC
set -u
if [ $# -ne 3 ]; then
  echo "usage: metrics.sh SERVER JQ STATIC" >&2
  exit 2
fi
SERVER=$1 JQ=$2 STATIC=$3
. "$(dirname "$0")/lib.sh"

start_server metrics --static "$STATIC"
# The exposition text now, in $WORK/m.$1 (GET /metrics counts itself only
# after it has answered, so each scrape sees the ones before it).
scrape() { curl -sS --max-time 30 "$BASE/metrics" >"$WORK/m.$1"; }
# value FILE SERIES: the sample's value, 0 when the series is not there.
value() { awk -v s="$2" '$1 == s { v = $2 } END { print v + 0 }' "$WORK/m.$1"; }
# grew SERIES N: the series grew by exactly N between scrapes a and b.
grew() {
  local a b
  a=$(value a "$1") b=$(value b "$1")
  same "$1 +$2" "$((b - a))" "$2"
}
rq() { curl -sS --max-time 60 -o /dev/null -w '%{http_code}' "$@"; }

job=$(curl -sS -H 'Content-Type: application/json' -d '{"analysis":"modal"}' \
  "$BASE/api/v1/jobs?wait=60" | "$JQ" /id)
scrape a
for _ in 1 2 3; do rq "$BASE/api/v1/jobs/$job" >/dev/null; done
for _ in 1 2; do rq "$BASE/api/v1/jobs/$job/result.csv" >/dev/null; done
rq "$BASE/api/v1/jobs?limit=2" >/dev/null
rq -I "$BASE/api/v1/health" >/dev/null
for u in /no/such/thing /api/v1/nope '/wp-login.php?x=1' /api/v1/jobs/abc/def; do
  same "GET $u is 404" "$(rq "$BASE$u")" 404
done
rq "$BASE/" >/dev/null
rq -X DELETE "$BASE/api/v1/jobs/0123456789abcdef" >/dev/null
rq -X PATCH "$BASE/api/v1/jobs/$job" >/dev/null
rq -X BREW "$BASE/api/v1/health" >/dev/null
rq "$BASE/metrics" >/dev/null
scrape b

T=ringdyn_http_requests_total
grew "$T{route=\"/api/v1/jobs/{id}\",method=\"GET\",status=\"200\"}" 3
grew "$T{route=\"/api/v1/jobs/{id}/result.csv\",method=\"GET\",status=\"200\"}" 2
grew "$T{route=\"/api/v1/jobs\",method=\"GET\",status=\"200\"}" 1
grew "$T{route=\"/api/v1/health\",method=\"HEAD\",status=\"200\"}" 1
grew "$T{route=\"other\",method=\"GET\",status=\"404\"}" 4
grew "$T{route=\"static\",method=\"GET\",status=\"200\"}" 1
grew "$T{route=\"/api/v1/jobs/{id}\",method=\"DELETE\",status=\"404\"}" 1
grew "$T{route=\"/api/v1/jobs/{id}\",method=\"PATCH\",status=\"405\"}" 1
grew "$T{route=\"/api/v1/health\",method=\"other\",status=\"405\"}" 1
grew "$T{route=\"/metrics\",method=\"GET\",status=\"200\"}" 2
# every request between the scrapes, and nothing else
sum() { awk -v p="$T{" 'index($1, p) == 1 { s += $2 } END { print s + 0 }' "$WORK/m.$1"; }
same "$T grew by the 17 requests between the scrapes (the first scrape's included)" \
  "$(($(sum b) - $(sum a)))" 17
# bounded labels: the routes are templates, never a URL that was asked for
# (start_server fetched the OpenAPI document)
routes=$(grep -o "^$T{route=\"[^\"]*\"" "$WORK/m.b" | sed 's/.*route="//;s/"$//' | sort -u | tr '\n' ' ')
same "$T routes are templates" "$routes" \
  "/api/v1/health /api/v1/jobs /api/v1/jobs/{id} /api/v1/jobs/{id}/result.csv /api/v1/openapi.json /metrics other static "
check "no raw URL in any label" bash -c "! grep -q '$job\|no/such\|wp-login\|nope\|0123456789abcdef' '$WORK/m.b'"

# the duration histogram counts the same requests, by route
H=ringdyn_http_request_duration_seconds
grew "${H}_count{route=\"/api/v1/jobs/{id}\"}" 5
grew "${H}_count{route=\"other\"}" 4
grew "${H}_bucket{route=\"/api/v1/jobs/{id}\",le=\"+Inf\"}" 5
check "$H buckets are cumulative and end at the count" awk -v r='route="/api/v1/jobs/{id}"' '
  index($1, "'"$H"'_bucket{" r) == 1 { if ($2 < last) bad = 1; last = $2 }
  index($1, "'"$H"'_count{" r) == 1 { count = $2 }
  END { exit (bad || last != count) }' "$WORK/m.b"
check "$H has a TYPE histogram line" grep -q "^# TYPE $H histogram$" "$WORK/m.b"

# jobs carry their analysis: counts and run times
curl -sS -o /dev/null -H 'Content-Type: application/json' \
  -d '{"analysis":"pretension","discretization":{"segments":8}}' "$BASE/api/v1/jobs?wait=120"
scrape c
check "ringdyn_jobs_total by analysis: modal" \
  grep -q '^ringdyn_jobs_total{analysis="modal",outcome="succeeded"} 1$' "$WORK/m.c"
check "ringdyn_jobs_total by analysis: pretension" \
  grep -q '^ringdyn_jobs_total{analysis="pretension",outcome="succeeded"} 1$' "$WORK/m.c"
check "ringdyn_job_run_seconds_count by analysis" \
  grep -q '^ringdyn_job_run_seconds_count{analysis="pretension",outcome="succeeded"} 1$' "$WORK/m.c"
check "a POST counted under /api/v1/jobs" \
  grep -q '^ringdyn_http_requests_total{route="/api/v1/jobs",method="POST",status="200"} 2$' "$WORK/m.c"

stop_server metrics "$SPID"
finish
