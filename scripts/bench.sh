#!/usr/bin/env bash
# `make bench`: runs each package's benchmark tool and regenerates docs/benchmarks.md from their JSON.
# BENCH_ONLY="name ..." limits the run to those entries of scripts/benchmarks.list.
set -uo pipefail
cd "$(dirname "$0")/.."
export PATH=/usr/bin:/bin:$PATH
BIOVISION_BENCH=1 bash scripts/setup.sh  # the benchmark-only data packages
set +u; source devel/setup.bash; set -u
out=out/bench
mkdir -p "$out"
export BIOVISION_SHARED=${BIOVISION_SHARED:-$(cd .. && pwd)/shared}
status=0
# Each line: <name> <command...>; the command must write $out/<name>.json.
while read -r name cmd; do
  [[ -z "$name" || "$name" == \#* ]] && continue
  # BENCH_ONLY="descriptor recognition" re-runs those entries; the report keeps the others' last JSON.
  [[ -n "${BENCH_ONLY:-}" && " $BENCH_ONLY " != *" $name "* ]] && continue
  echo "bench: $name"
  # Tools print their JSON and progress; keep both in a log, the report comes from the JSON file.
  if ! eval "$cmd" >"$out/$name.log" 2>&1; then echo "bench: $name FAILED (see $out/$name.log)"; status=1; fi
done < scripts/benchmarks.list
/usr/bin/python3 scripts/bench_report.py "$out" docs/benchmarks.md || status=1
exit $status
