# Shared by the robustness scripts (tests/run_*.sh), sourced after they set
# "here" to the tests folder:
#   base        the small scene they vary (robustness/small.prm);
#   fail TEXT   prints TEXT and fails the test;
#   set_entry ENTRY VALUE < PRM > PRM2   the scene with one entry changed;
#   run_scene PRM RANKS NAME     runs the program (uses $executable) on PRM
#                                into results/ (removed first), output in
#                                out.txt and err.txt; fails naming NAME.
#   wait_for_step N OUTPUT PID   waits (up to 30 s) until the run PID has
#                                printed step N into OUTPUT; fails if not.
#   read_part ARG   a benchmark script's part, from its second argument:
#                   "quick" (the Debug build's few checks: sets quick),
#                   "core" (the default tier's checks) or none (all);
#   extended        whether the part runs the checks kept for the extended
#                   tier (the test NAME_all runs them): variants whose code
#                   paths the core ones cover in a twin.
base=$here/robustness/small.prm
fail() { echo "$*"; exit 1; }
read_part() {
  quick='' part=all
  case $1 in
    "") ;;
    quick) quick=quick ;;
    core) part=core ;;
    *) fail "unknown part <$1>; accepted: quick, core or none" ;;
  esac
}
extended() { [ "$part" = all ] && [ -z "$quick" ]; }
set_entry() {
  sed -e "s|^\( *set $1 *=\).*|\1 $2|"
}
run_scene() {
  rm -rf results
  "$here/run_mpi.sh" "$2" "$executable" "$1" > out.txt 2> err.txt \
    || fail "$3: the run failed: $(cat err.txt)"
}
wait_for_step() {
  local i
  for i in $(seq 1 600); do
    grep -q "^Step *$1 " "$2" 2> /dev/null && return 0
    kill -0 "$3" 2> /dev/null || break
    sleep 0.05
  done
  fail "The run did not reach step $1: $(tail -3 "$2")"
}
