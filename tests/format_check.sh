#!/usr/bin/env bash
# Fails when a C++ file of the tree differs from what the repository's .clang-format makes of it,
# printing the first lines of each difference. Skips (77) without clang-format.
set -uo pipefail
root="$1"
command -v clang-format >/dev/null || { echo "clang-format not installed: skipped"; exit 77; }
cd "$root" || exit 1
status=0
while IFS= read -r -d '' f; do
  if ! clang-format --style=file "$f" | diff -q "$f" - >/dev/null; then
    echo "not clang-format clean: $f"
    clang-format --style=file "$f" | diff "$f" - | head -8
    status=1
  fi
done < <(find src tests tools bench fuzz \( -name '*.cpp' -o -name '*.h' \) -print0 | sort -z)
((status == 0)) && echo "every C++ file is clang-format clean"
exit $status
