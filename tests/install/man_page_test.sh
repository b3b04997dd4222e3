#!/usr/bin/env bash
# A manual page follows its program's command line: every option that `PROGRAM --help` and
# `PROGRAM MODE --help` list is documented there, every --option the page names is one the
# program takes, every exit status of the "Exit status:" block of `PROGRAM --help` is in the
# page's EXIT STATUS section, and groff formats the page without a warning.
#   man_page_test.sh PAGE PROGRAM [MODE...]
#   (docs/rad.1 build/rad batch serve convert; docs/rad-gen.1 build/tools/rad-gen)
set -euo pipefail
page=$1 program=$2
shift 2
d=$(mktemp -d)
trap 'rm -rf "$d"' EXIT
status=0

for mode in "" "$@"; do
  # shellcheck disable=SC2086
  "$program" $mode --help >"$d/help"
  # Option lines: two spaces, then -x,--name or --name.
  grep -oE '^  (-[a-zA-Z],)?--[a-z][a-z0-9-]*' "$d/help" | grep -oE -- '--[a-z0-9-]+' >>"$d/options"
done
sort -u "$d/options" -o "$d/options"
[ "$(wc -l <"$d/options")" -ge 3 ] || { echo "too few options read from --help"; exit 1; }

# The options the page names (in roff a hyphen in an option is written \-; font changes such as
# \fB and \fR dropped first, so that they do not run on from a name).
sed 's/\\f[BIRP]//g' "$page" | grep -oE '\\-\\-[a-z][a-z0-9\\-]*[a-z0-9]' | sed 's/\\-/-/g' |
  sort -u >"$d/named"
while read -r option; do
  grep -qxF -- "$option" "$d/named" || { echo "not in the man page: $option"; status=1; }
done <"$d/options"
while read -r option; do
  grep -qxF -- "$option" "$d/options" || { echo "the man page names $option, which no mode takes"; status=1; }
done <"$d/named"

# Exit statuses: the numbers of the "Exit status:" block of PROGRAM --help, if it has one.
{ "$program" --help | sed -n '/^Exit status:/,$p' | grep -oE '(^| )[0-9]+( |,|$)' || true; } |
  tr -d ' ,' | sort -u >"$d/codes"
sed -n '/^\.SH EXIT STATUS/,/^\.SH /p' "$page" >"$d/exit"
while read -r code; do
  grep -qE "^\.BR? ([0-9]+ \", \" )?$code( |$)|^\.BR? $code\b" "$d/exit" ||
    { echo "exit status $code is not in the man page's EXIT STATUS"; status=1; }
done <"$d/codes"

if command -v groff >/dev/null; then
  warnings=$(groff -man -Tutf8 -ww -z "$page" 2>&1)
  [ -z "$warnings" ] || { echo "groff warns: $warnings"; status=1; }
fi

((status == 0)) &&
  echo "$(basename "$page"): $(wc -l <"$d/options") options, exit statuses $(tr '\n' ' ' <"$d/codes")"
exit $status
