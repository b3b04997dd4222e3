#!/usr/bin/env bash
# Every source unit has its tests findable by name: src/<stage>/<unit>.cpp has
# tests/<stage>/<unit>_test.cpp, or a line "- `<unit>`: ..." in tests/<stage>/README.md saying
# where they are. Prints each unit that has neither.
set -uo pipefail
cd "$1" || exit 1
missing=0
for f in src/*/*.cpp; do
  stage=$(basename "$(dirname "$f")") unit=$(basename "$f" .cpp)
  [ -f "tests/$stage/${unit}_test.cpp" ] && continue
  grep -q "^- \`$unit\`:" "tests/$stage/README.md" 2>/dev/null && continue
  echo "no tests/$stage/${unit}_test.cpp and no line for it in tests/$stage/README.md: $f"
  missing=1
done
((missing == 0)) && echo "every source unit's tests are findable by name"
exit $missing
