#!/usr/bin/env bash
# Functions of a screen or less in the identification core: no function definition in
# host/identification/*.cpp longer than 60 lines, signature to closing brace. Counted on the
# clang-format layout (a definition starts at a column-0 line, ends at a column-0 "}").
# Usage: function_length_test.sh SOURCE_DIR [LIMIT]
set -uo pipefail
src=$1
limit=${2:-60}
long=$(awk -v LIMIT="$limit" '
  FNR == 1 { start = 0 }
  /^(namespace|using|#|\/\/|struct|class|enum|union|static_assert|extern)/ {
    if ($0 !~ /\{$/ || $0 ~ /^namespace/) { start = 0; next }
  }
  /^[A-Za-z_]/ && start == 0 { start = FNR; name = $0 }
  start > 0 && FNR == start && /;[ \t]*$/ && $0 !~ /\{/ { start = 0; next }
  /^}/ {
    if (start > 0 && $0 ~ /^}[ \t]*$/ && FNR - start + 1 > LIMIT)
      printf "%s:%d: %d lines: %s\n", FILENAME, start, FNR - start + 1, name
    start = 0
  }' "$src"/host/identification/*.cpp)
if [ -n "$long" ]; then
  echo "FAIL: functions longer than $limit lines:"; echo "$long"; exit 1
fi
echo "PASS: every function in host/identification is at most $limit lines"
