#!/bin/sh
# script_case.sh CMAKE -D... -P CASE.cmake: runs a cmake -P test case and exits with
# its code, or with 77 (ctest's SKIP_RETURN_CODE) when it ended well after a line
# "SKIPPED: reason" (tests/skip.cmake): cmake -P itself exits 0 or 1 only. A case
# that failed after saying SKIPPED stays failed.
output=$("$@" 2>&1)
code=$?
printf '%s\n' "$output"
if [ "$code" -eq 0 ] && printf '%s\n' "$output" | grep -q '^SKIPPED: '; then
  exit 77
fi
exit "$code"
