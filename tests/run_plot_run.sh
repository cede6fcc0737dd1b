#!/bin/bash
# scripts/plot_run.py on a small fake output folder (a time series with
# reaction_ columns and an appended column, two 2D contact profiles), with
# Debian's /usr/bin/python3:
#  - it writes forces.png, contact.png, iterations.png and
#    pressure_profiles.png into the folder's plots/, each a non-empty PNG;
#  - a second call replaces its own plots;
#  - a file of the user under one of its names is refused (exit 1) and
#    left as it was; a missing folder is refused (exit 1).
#   run_plot_run.sh   (no arguments; works in the current folder)
set -u
here=$(cd "$(dirname "$0")" && pwd)
script=$here/../scripts/plot_run.py
python=/usr/bin/python3
fail() { echo "$*"; exit 1; }

folder=plot_run_fake
rm -rf "$folder" && mkdir "$folder" || fail "Cannot create $folder."
{
  echo "step,time,active_set_iterations,unilateral_nodes,compliance_nodes,no_contact_nodes,total_contact_force,max_von_mises,wall_time,krylov_iterations,time_step,error_estimate,reaction_clamped_x,reaction_clamped_y,reaction_prescribed_1_y,later_column"
  echo "1,0.25,3,0,4,1,1.5,10,0.01,0,0.25,0.01,0.1,-1.5,1.4,a"
  echo "2,0.5,2,1,3,1,2.5,11,0.02,0,0.25,0.01,0.2,-2.5,2.3,b"
  echo "3,0.75,1,1,4,0,3.0,12,0.03,0,0.25,0.01,0.3,-3.0,2.8,c"
  echo "4,1,1,2,3,0,3.2,12,0.04,0,0.25,0.01,0.3,-3.2,3.0,d"
} > "$folder/time_series.csv"
for profile in "0002 0.5 1" "0004 1 2"; do
  read -r step time p <<< "$profile"
  {
    echo "x,y,time,u_nu,compliance_pressure,foundation_pressure,contact_pressure,nodal_force,weight,status"
    for x in 0 0.25 0.5 0.75 1; do
      pressure=$(awk "BEGIN { print $p * (1 + $x) }")
      echo "$x,0,$time,0.001,$pressure,0,$pressure,0.1,0.25,1"
    done
  } > "$folder/contact_profile_$step.csv"
done

"$python" "$script" "$folder" > out.txt 2> err.txt \
  || fail "plot_run.py failed: $(cat err.txt)"
signature=$(printf '\211PNG\r\n\032\n' | od -An -tx1)
for name in forces contact iterations pressure_profiles; do
  file=$folder/plots/$name.png
  [ -s "$file" ] || fail "$file is missing or empty."
  [ "$(head -c 8 "$file" | od -An -tx1)" = "$signature" ] \
    || fail "$file does not start with the PNG signature."
  grep -qx "$file" out.txt || fail "plot_run.py did not print $file: $(cat out.txt)"
done

"$python" "$script" "$folder" > out.txt 2> err.txt \
  || fail "A second call did not replace its own plots: $(cat err.txt)"

echo "the user's file" > "$folder/plots/contact.png"
"$python" "$script" "$folder" > out.txt 2> err.txt
status=$?
[ $status -eq 1 ] || fail "A file of the user in plots/: exit status $status, not 1."
grep -q "contact.png" err.txt || fail "The refusal does not name the file: $(cat err.txt)"
[ "$(cat "$folder/plots/contact.png")" = "the user's file" ] \
  || fail "plot_run.py replaced a file it did not write."

"$python" "$script" "$folder/missing" > out.txt 2> err.txt
status=$?
[ $status -eq 1 ] || fail "A missing folder: exit status $status, not 1."
grep -q "$folder/missing" err.txt || fail "The error does not name the folder: $(cat err.txt)"
echo "plot_run.py: all checks passed"
