#!/usr/bin/env bash
# One scene solved across MPI ranks (src/solver/distribute.h), against the plain process.
#   mpi_test.sh CASE RAD RAD_GEN SCENES_DIR HAVE_MPI
# CASE: same-bytes | checkpoints | failures. Skips (77) when rad was built without Open MPI or
# mpirun is missing (tools/test installs both).
set -u
case_="$1" rad="$2" gen="$3" scenes="$4" have_mpi="$5"
[ "$have_mpi" = "ON" ] || { echo "rad was built without Open MPI (libopenmpi-dev): skipped"; exit 77; }
command -v mpirun >/dev/null || { echo "mpirun is missing (apt-get install openmpi-bin): skipped"; exit 77; }
if [ "$(id -u)" -eq 0 ]; then export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1; fi
d=$(mktemp -d)
trap 'rm -rf "$d"' EXIT
fail() { echo "FAIL: $*"; exit 1; }
# mpirun under a time limit: a rank that waits forever must fail the test, not hang it.
mpi() { local n="$1"; shift; timeout 300 mpirun -np "$n" --oversubscribe "$rad" "$@"; }

same_bytes() {
  "$gen" building "$d/building.des" --size 3200 --lights-reach 1 >/dev/null || fail "rad-gen"
  "$gen" building "$d/lit.des" --size 3200 --point-lights >/dev/null || fail "rad-gen lights"
  "$rad" convert "$scenes/cornell_box.des" "$d/cornell.obj" -q || fail "convert"
  # name|ranks|scene|options (1, 2, 3 and 4 ranks): nested objects and OFF files, Lights lists,
  # a run without overshooting, a model with its automatic hierarchy, a run to convergence
  # (the stop test on exact sums), point lights (every rank shoots each), and light groups (the
  # groups' shares go with every shot to every rank, their states come back with the polygons).
  local runs=(
    "original|1 2 4|$scenes/original_style.des|--max-shots 30"
    "building|2 3|$d/building.des|--max-shots 60"
    "no-overshoot|2|$scenes/furnace_box.des|--max-shots 20 --no-overshoot"
    "model|3|$d/cornell.obj|--max-shots 20"
    "converged|2|$scenes/cornell_box.des|--converge 0.03"
    "lights|2|$d/lit.des|--max-shots 40"
    "groups|2 3|$scenes/cornell_box_groups.des|--max-shots 40"
  )
  for run in "${runs[@]}"; do
    IFS='|' read -r name ranks scene opts <<<"$run"
    # shellcheck disable=SC2086
    # The image by final gather too: rank 0 renders from the ranks' polygons.
    "$rad" "$scene" "$d/$name.ply" -q --threads 2 $opts --image "$d/$name.pfm" --size 40x30 ||
      fail "$name: plain run"
    for n in $ranks; do
      # shellcheck disable=SC2086
      mpi "$n" "$scene" "$d/$name-$n.ply" -q --threads 1 $opts --stats-json "$d/$name-$n.json" \
        --image "$d/$name-$n.pfm" --size 40x30 || fail "$name: mpirun -np $n"
      cmp "$d/$name.ply" "$d/$name-$n.ply" || fail "$name: $n ranks wrote other bytes"
      cmp "$d/$name.pfm" "$d/$name-$n.pfm" || fail "$name: $n ranks rendered other pixels"
    done
    echo "$name: $ranks ranks write the plain run's bytes"
  done
  python3 - "$d/building-3.json" <<'PY' || fail "stats of 3 ranks"
import json, sys
j = json.load(open(sys.argv[1]))
m = j["mpi"]
assert m["ranks"] == 3 and len(m["per_rank"]) == 3, m
assert all(r["vertices"] > 0 and r["rays"] > 0 for r in m["per_rank"]), m
assert sum(r["vertices"] for r in m["per_rank"]) <= j["solver"]["vertices"], (m, j["solver"])
assert 0 < m["shot_source_bytes_mean"] < 200000, m
PY
}

checkpoints() {
  local s="$scenes/cornell_box.des" o=(-q --threads 1)
  "$rad" "$s" "$d/full.ply" --max-shots 40 "${o[@]}" || fail "plain run"
  # Stopped at 15 shots under one rank count, taken to 40 under another (or none).
  local pairs=("2 2" "2 0" "0 3")
  for pair in "${pairs[@]}"; do
    read -r a b <<<"$pair"
    local ck="$d/run-$a-$b.ckpt" out="$d/run-$a-$b.ply"
    if [ "$a" = 0 ]; then "$rad" "$s" "$out" --max-shots 15 --checkpoint "$ck" "${o[@]}"; else
      mpi "$a" "$s" "$out" --max-shots 15 --checkpoint "$ck" "${o[@]}"; fi || fail "first part $pair"
    [ -s "$ck" ] || fail "no checkpoint ($pair)"
    if [ "$b" = 0 ]; then "$rad" "$s" "$out" --max-shots 40 --checkpoint "$ck" "${o[@]}"; else
      mpi "$b" "$s" "$out" --max-shots 40 --checkpoint "$ck" "${o[@]}"; fi || fail "resume $pair"
    cmp "$d/full.ply" "$out" || fail "ranks $a then $b: other bytes than a run never stopped"
    echo "checkpoint of $a ranks resumed by $b (0: the plain process): same bytes"
  done
  # A checkpoint every shot, under 2 ranks: the same answer too.
  mpi 2 "$s" "$d/every.ply" --max-shots 40 --checkpoint "$d/every.ckpt" --checkpoint-every 0 \
    "${o[@]}" || fail "checkpoint every shot"
  cmp "$d/full.ply" "$d/every.ply" || fail "checkpointing every shot changed the answer"
}

failures() {
  # A scene every rank refuses: one error naming the file and the rank, non-zero, no output.
  local err
  err=$(mpi 2 "$scenes/bad/bad_number.des" "$d/bad.ply" 2>&1 >/dev/null)
  [ $? -ne 0 ] || fail "a bad scene exited 0"
  grep -q "bad_number.des:4:27: error" <<<"$err" || fail "no located error: $err"
  grep -q "rad rank 0 of 2" <<<"$err" || fail "the error names no rank: $err"
  [ ! -e "$d/bad.ply" ] || fail "a bad scene wrote output"
  # Ranks that read different scenes (a file that differs between nodes): an error, no hang.
  cp "$scenes/cornell_box.des" "$d/scene0.des"
  cp "$scenes/furnace_box.des" "$d/scene1.des"
  timeout 120 mpirun -np 2 --oversubscribe bash -c \
    "exec '$rad' '$d/scene'\$OMPI_COMM_WORLD_RANK.des '$d/differ.ply' -q" 2>"$d/differ.err" &&
    fail "ranks with different scenes ran"
  grep -q "the ranks do not hold the same solve" "$d/differ.err" ||
    fail "different scenes: $(cat "$d/differ.err")"
  [ ! -e "$d/differ.ply" ] || fail "ranks with different scenes wrote output"
  # Modes that do not split one scene are refused under several ranks.
  mpi 2 batch "$d/batch" "$scenes/cornell_box.des" -q 2>"$d/batch.err" && fail "batch ran"
  grep -q "shard" "$d/batch.err" || fail "batch refusal: $(cat "$d/batch.err")"
  # A rank killed mid-solve ends the whole run, naming the rank, instead of a hang.
  mpi 2 "$scenes/cornell_box.des" "$d/killed.ply" -q --threads 1 --converge 1e-9 \
    >"$d/killed.log" 2>&1 &
  local job=$! victim="" i
  for i in $(seq 100); do
    # The ranks themselves (mpirun's and timeout's command lines hold the same words).
    victim=$(pgrep -f "^$rad $scenes/cornell_box.des $d/killed.ply" | sort -n | tail -1)
    [ "$(pgrep -c -f "^$rad $scenes/cornell_box.des $d/killed.ply")" -ge 2 ] && break
    sleep 0.1
  done
  sleep 1
  kill -9 "$victim" || fail "no rank to kill"
  wait "$job"
  local status=$?
  [ "$status" -ne 0 ] && [ "$status" -ne 124 ] || fail "mpirun exited $status after a rank was killed"
  grep -q "rank [01]" "$d/killed.log" || fail "the failure names no rank: $(cat "$d/killed.log")"
  [ ! -e "$d/killed.ply" ] || fail "a killed run wrote output"
  echo "a refused scene, a refused mode and a killed rank each end the run with an error"
}

case "$case_" in
  same-bytes) same_bytes ;;
  checkpoints) checkpoints ;;
  failures) failures ;;
  *) fail "unknown case $case_" ;;
esac
echo "ok"
