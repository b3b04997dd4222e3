#!/usr/bin/env bash
# rad batch sharded by GNU parallel: two workers, one scene failing, a shard run again (its
# solved scenes skipped, files untouched) and one shard run twice at once (nothing torn).
#   batch_parallel_test.sh RAD SCENES_DIR
set -u
rad="$1" scenes="$2"
command -v parallel >/dev/null || { echo "GNU parallel is not installed (apt-get install parallel): skipped"; exit 77; }
d=$(mktemp -d)
trap 'rm -rf "$d"' EXIT
fail() { echo "FAIL: $*"; exit 1; }
printf '%s\n' "$scenes/parallel_squares.des" "$scenes/bad/unknown_keyword.des" \
  "$scenes/furnace_box.des" "$scenes/cornell_box.des" >"$d/list.txt"
opts=(--max-shots 10 --size 32x32 -q)

# Shard 0: parallel_squares, furnace_box; shard 1: unknown_keyword (fails), cornell_box.
parallel --will-cite -j2 "$rad" batch "$d/out" "$d/list.txt" --shard {}/2 "${opts[@]}" ::: 0 1
status=$?
[ "$status" -eq 1 ] || fail "expected one failed shard, parallel exited $status"
for n in parallel_squares furnace_box cornell_box; do
  for e in ply png json; do [ -s "$d/out/$n.$e" ] || fail "missing $n.$e"; done
done
[ ! -e "$d/out/unknown_keyword.ply" ] || fail "the broken scene wrote a mesh"
check_summary() {
  python3 - "$1" <<'PY' || fail "batch.json: see above"
import json, sys
j = json.load(open(sys.argv[1]))
s = j["scenes"]
assert j["schema"] == "rad-batch" and j["version"] == 1, j
assert sorted(s) == ["cornell_box", "furnace_box", "parallel_squares", "unknown_keyword"], sorted(s)
bad = s["unknown_keyword"]
assert bad["status"] == "failed" and "unknown keyword" in bad["detail"], bad
for n in ["cornell_box", "furnace_box", "parallel_squares"]:
    assert s[n]["status"] == "ok" and 1 <= s[n]["shots"] <= 10 and s[n]["vertices"] > 0, s[n]
assert {r["shard"] for r in s.values()} == {0, 1}, s
PY
}
check_summary "$d/out/batch.json"

# Shard 0 requeued: both scenes skipped, outputs and summary untouched.
stamp() { stat -c '%n %y %s' "$d"/out/parallel_squares.* "$d"/out/furnace_box.* "$d/out/batch.json"; }
before=$(stamp)
out=$("$rad" batch "$d/out" "$d/list.txt" --shard 0/2 --max-shots 10 --size 32x32) || fail "rerun failed"
[ "$(grep -c 'skipped' <<<"$out")" -ge 2 ] || fail "rerun did not skip: $out"
[ "$(stamp)" = "$before" ] || fail "rerun touched the outputs"
check_summary "$d/out/batch.json"
# Other options are another job: solved again.
"$rad" batch "$d/out" "$d/list.txt" --shard 0/2 --max-shots 11 --size 32x32 -q || fail "re-solve failed"
[ "$(stamp)" != "$before" ] || fail "changed options did not solve again"

# The same shard twice at once: both solve, every file whole, the summary well formed.
parallel --will-cite -j2 -N0 "$rad" batch "$d/twice" "$d/list.txt" --shard 0/2 "${opts[@]}" ::: a b ||
  fail "duplicated shard failed"
python3 - "$d/twice/batch.json" <<'PY' || fail "duplicated shard: batch.json"
import json, sys
s = json.load(open(sys.argv[1]))["scenes"]
assert sorted(s) == ["furnace_box", "parallel_squares"] and all(r["status"] == "ok" for r in s.values()), s
PY
for n in parallel_squares furnace_box; do
  head -c 3 "$d/twice/$n.ply" | grep -q ply || fail "$n.ply torn"
  python3 -c "import json,sys; json.load(open(sys.argv[1]))" "$d/twice/$n.json" || fail "$n.json torn"
done
[ -z "$(ls "$d/twice" | grep tmp)" ] || fail "temporary files left: $(ls "$d/twice")"
echo "batch under GNU parallel: ok"
