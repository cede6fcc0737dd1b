#!/bin/bash
# Hostile input, entry by entry: the printed defaults (the benchmark scene of
# parameters/default.prm, with every entry) on a coarse mesh and 4 steps;
# every entry in turn set to hostile values: empty, nan, inf, -1, 0, 1e300,
# a word, a string of 3000 characters. Each run, under a time limit, must
# exit with 0, or with 1 and a message ("Error" on standard error); never
# crash (a signal, another status), hang (timeout), or write nan or inf into
# a CSV output. Two runs go at a time.
#
# A run costs about half a second (mostly loading the libraries and starting
# MPI), so to stay within the suite's time every entry gets 1 of the 8
# values, in turn (entry i the value i modulo 8), which gives every value to
# every eighth entry; "all" as second argument runs all 8 for every entry
# (about 3 minutes on 2 cores).
#   run_hostile_input.sh EXECUTABLE [all]
set -u
executable=$1 coverage=${2:-}
# A single process needs no MPI daemon.
export OMPI_MCA_ess_singleton_isolated=1
rm -rf work && mkdir work && cd work || exit 1

"$executable" --print-parameters base.prm > /dev/null || { echo "--print-parameters failed"; exit 1; }
sed -i -e 's/^\( *set Subdivisions *=\).*/\1 4/' \
       -e 's/^\( *set Time step *=\).*/\1 0.25/' \
       -e 's/^\( *set Profile times *=\).*/\1 0.5/' \
       -e 's/^\( *set Print timing summary *=\).*/\1 false/' \
       -e 's/^\( *set Output directory *=\).*/\1 results/' base.prm

long=$(printf 'x%.0s' $(seq 3000))
values=("" nan inf -1 0 1e300 word "$long")

# One run: entry number (the line of base.prm) and value number. Prints
# nothing if the run behaved, otherwise what went wrong.
one_run() { # line value_index
  local dir="run_$1_$2" value=${values[$2]}
  mkdir "$dir"
  # The value goes in literally (awk, not sed: no escaping of / or &).
  awk -v line="$1" -v value="$value" \
    'NR == line { sub(/=.*/, "= " value) } { print }' base.prm > "$dir/scene.prm"
  local entry
  entry=$(sed -n "$1s/^ *set \([^=]*[^ =]\) *=.*/\1/p" base.prm)
  (cd "$dir" && timeout 30 "$executable" scene.prm > out.txt 2> err.txt)
  local status=$?
  local what="<$entry> = <${value:0:20}>"
  case $status in
    0) ;;
    1) grep -q "Error" "$dir/err.txt" || echo "$what: status 1 without a message." ;;
    124) echo "$what: no end within 30 s (hang)." ;;
    *) echo "$what: exit status $status (crash): $(tail -3 "$dir/err.txt")" ;;
  esac
  if [ -d "$dir/results" ] && grep -rilq --include='*.csv' '\bnan\b\|\binf\b' "$dir/results"; then
    echo "$what: nan or inf in a CSV output."
  fi
  rm -rf "$dir"
}
export -f one_run
export executable long

lines=$(grep -n '^ *set ' base.prm | cut -d: -f1)
jobs=()
i=0
for line in $lines; do
  for j in 0 1 2 3 4 5 6 7; do
    [ "$coverage" = all ] || [ "$j" -lt 1 ] || continue
    jobs+=("$line $(((i + j) % 8))")
  done
  i=$((i + 1))
done
# values[] cannot be exported as an array: pass it through a file.
printf '%s\n' "${values[@]}" > values.txt
problems=$(printf '%s\n' "${jobs[@]}" | xargs -P 2 -L 1 bash -c '
  mapfile -t values < values.txt
  one_run "$0" "$1"')
if [ -n "$problems" ]; then
  echo "$problems"
  exit 1
fi
echo "${#jobs[@]} runs ($(echo "$lines" | wc -w) entries, each with $((${#jobs[@]} / $(echo "$lines" | wc -w))) of the ${#values[@]} hostile values): each ended with status 0, or 1 and a message; no crash, hang or nan in an output."
