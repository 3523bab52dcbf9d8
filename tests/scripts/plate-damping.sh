#!/usr/bin/env bash
# The damped bouncing plate (edp/bouncing-plate.edp -rayleigh aM,bK,
# method.md §9), T = 0.6 (two impacts):
# - every NBM run is impenetrable (maxPenetration = 0, also checked by the
#   script itself);
# - undamped, the dissipated energy D is 0; damped, D > 1% of m g h0 and the
#   final energy is below the undamped run's;
# - massless boundary (energy conserving without damping): E + D stays within
#   0.5% of m g h0 of E(0) (the balance closes to the time discretisation);
# - the paper's NBM (consistent mass) dissipates too (its touch-downs lose
#   the contact nodes' kinetic energy, so E + D only decreases: reported).
#   plate-damping.sh <build> <repo> [bouncing-plate.edp args...]
set -eu
build=$1 repo=$2
. "$repo/scripts/lib.sh"
shift 2
run() { bash "$repo/tests/scripts/run-freefem.sh" "$build" "$repo" "$repo/edp/bouncing-plate.edp" \
          -T 0.6 -dt 5e-4 -vtkFrames 0 -snapshots 0 "$@" | grep '^bouncing-plate:'; }
fail() { echo "FAIL: $*"; exit 1; }
check() { awk -v x="$1" -v y="$2" "BEGIN { exit !(x $3 y) }"; }

free=$(run -mass redistributed -rayleigh 0,0 -out damping-none)
damped=$(run -mass redistributed -rayleigh 2,1e-4 -out damping-massless)
paper=$(run -mass consistent -rayleigh 2,1e-4 -out damping-consistent)
mgh0=$(summary_value "$damped" mgh0)
for line in "$free" "$damped" "$paper"; do
  echo "$line"
  [ "$(summary_value "$line" maxPenetration)" = 0 ] || fail "penetration: $line"
done
d0=$(summary_value "$free" dissipated)
d=$(summary_value "$damped" dissipated)
dp=$(summary_value "$paper" dissipated)
b=$(summary_value "$damped" balance)
e0=$(summary_value "$free" energyFinal)
e=$(summary_value "$damped" energyFinal)
printf 'undamped D = %s; massless D = %s mgh0, max |E + D - E0| = %s mgh0; paper NBM D = %s mgh0\n' \
  "$d0" "$(awk -v x="$d" -v m="$mgh0" 'BEGIN { printf "%.4g", x / m }')" \
  "$(awk -v x="$b" -v m="$mgh0" 'BEGIN { printf "%.3g", x / m }')" \
  "$(awk -v x="$dp" -v m="$mgh0" 'BEGIN { printf "%.4g", x / m }')"
check "$d0" 0 "==" || fail "undamped run dissipated $d0"
check "$d" "0.01 * $mgh0" ">" || fail "damped run dissipated only $d"
check "$dp" "0.01 * $mgh0" ">" || fail "paper NBM damped run dissipated only $dp"
check "$e" "$e0" "<" || fail "damped final energy $e not below the undamped $e0"
check "$b" "0.005 * $mgh0" "<" || fail "massless balance |E + D - E0| = $b >= 0.5% of mgh0"
echo "plate-damping: ok"
