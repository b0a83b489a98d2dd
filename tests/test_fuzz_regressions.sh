#!/usr/bin/env bash
# Every input the scene parser's fuzz target keeps (tests/fuzz/regressions: crashes it found, and the
# scenes of issue 81 that crashed or allocated past the machine) through `rift check`: a scene
# (status 0) or a located error (status 2), never a crash, an exception of another kind or a hang.
set -euo pipefail
rift="$1"
regressions="$(dirname "$0")/fuzz/regressions"
err=$(mktemp)
trap 'rm -f "$err"' EXIT
count=0
for f in "$regressions"/*; do
  set +e
  timeout 60 "$rift" check "$f" > /dev/null 2> "$err"
  status=$?
  set -e
  if [ "$status" -ne 0 ] && [ "$status" -ne 2 ]; then
    echo "FAIL: rift check $f exited with status $status:"
    cat "$err"
    exit 1
  fi
  count=$((count + 1))
done
echo "fuzz regressions: $count inputs, each a scene or a located error"
