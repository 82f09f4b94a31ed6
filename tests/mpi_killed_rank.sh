#!/usr/bin/env bash
# A rank killed mid-run (issue 13): `mpirun -np 3 smithlab trace` with rank 2 killed (SIGKILL) once a few cells are
# done. The run must end with a non-zero exit, rank 0 saying which cell each rank held, and with the finished cell
# files kept and no temporaries; the same command without MPI then traces only the missing cells, and its outputs are
# a fresh run's, byte for byte. Args: EXE MPIEXEC SCENE WORK_DIR.
set -u
exe=$1 mpiexec=$2 scene=$3 work=$4
rm -rf "$work" && mkdir -p "$work" && cd "$work" || exit 1
launcher=("$mpiexec")
openmpi=0
if "$mpiexec" --version 2>&1 | grep -q "Open MPI\|OpenRTE"; then
  openmpi=1
  launcher+=(--oversubscribe)
  # Open MPI 4 waits odls_base_sigkill_timeout (1 s) after a rank died, sends SIGTERM, and SIGKILL after as long again
  # (measured: with 10, the ranks got SIGTERM 10 s after the kill). On a loaded 2-core machine rank 0 once in ~8 runs
  # neither printed its notes nor removed its stage within the 1 s: 3 s leaves it room. (An ORTE parameter: 4 only.)
  "$mpiexec" --version 2>&1 | grep -q "Open MPI) 4\.\|OpenRTE) 4\." && launcher+=(--mca odls_base_sigkill_timeout 3)
  [ "$(id -u)" = 0 ] && launcher+=(--allow-run-as-root)
fi
fail() {
  echo "mpi_killed_rank: $*"
  for f in killed.log resumed.log; do [ -f $f ] && { echo "--- $f:"; cat $f; }; done
  exit 1
}
cells() { find "$1/cells" -name 'cell-*.csv' 2>/dev/null | wc -l; }

"${launcher[@]}" -np 3 "$exe" trace "$scene" --output out --threads 1 > killed.log 2>&1 &
launched=$!
# Rank 2's process first (scanning /proc takes a while on a loaded machine: done after the cells appeared, it once let
# the whole run finish before the kill), then the kill as soon as 3 cells are done.
# A rank of this run: its working directory is this test's (not a leftover of another run), rank 2 in its environment.
is_rank2() {
  [ "$(readlink "/proc/$1/cwd" 2>/dev/null)" = "$PWD" ] &&
    tr '\0' '\n' < "/proc/$1/environ" 2>/dev/null | grep -qx "OMPI_COMM_WORLD_RANK=2\|PMIX_RANK=2\|PMI_RANK=2"
}
victim=""
for _ in $(seq 1200); do
  for p in $(pgrep -f -- "trace $scene"); do
    is_rank2 "$p" && victim=$p
  done
  [ -n "$victim" ] && break
  sleep 0.05
done
[ -n "$victim" ] || fail "found no process of rank 2 in 60 s"
for _ in $(seq 1200); do
  [ "$(cells out)" -ge 3 ] && break
  sleep 0.05
done
[ "$(cells out)" -ge 3 ] || fail "no cell finished in 60 s"
is_rank2 "$victim" || fail "the run ended before rank 2 could be killed"
kill -9 "$victim"
wait $launched
rc=$?
[ $rc -ne 0 ] || fail "the run exited 0 after rank 2 was killed"
grep -q "stopped by a signal" killed.log || fail "rank 0 said nothing when mpirun stopped it"
grep -q "rank 2 held cell [0-9]* (ggx(alpha=" killed.log || fail "rank 0 did not name the cell rank 2 held"
[ $openmpi = 0 ] || grep -q "process rank 2" killed.log || fail "mpirun did not name rank 2"
kept=$(cells out)
[ "$kept" -ge 3 ] && [ "$kept" -lt 24 ] || fail "$kept of 24 cell files kept (want some, not all)"
leftover=$(find out -name '*smithlab-partial*' | head -3)
[ -z "$leftover" ] || fail "temporaries left behind: $leftover"

"$exe" trace "$scene" --output out --threads 2 > resumed.log 2>&1 || fail "the rerun failed"
grep -qx "reused $kept" resumed.log || fail "the rerun did not reuse the $kept finished cells"
grep -qx "traced $((24 - kept))" resumed.log || fail "the rerun did not trace exactly the $((24 - kept)) missing cells"
"$exe" trace "$scene" --output fresh --threads 2 > fresh.log 2>&1 || fail "the fresh run failed"
for f in albedo.csv $(cd fresh && ls cells/*.csv); do
  cmp -s "out/$f" "fresh/$f" || fail "$f after the resumed run differs from a fresh run's"
done
echo "mpi_killed_rank: rank 2 killed with $kept of 24 cells done (exit $rc); the rerun traced $((24 - kept)); outputs identical"
