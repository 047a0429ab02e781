#!/usr/bin/env bash
# Throughput of fibrenet, LAMMPS and ESyS-Particle on one fibre bed (docs/performance.md):
# fibrenet's bench writes its bed after the warmup; LAMMPS and ESyS-Particle (Debian's
# lammps and esys-particle, installed here when missing) start from that state and time the
# same number of steps. Prints one line per code and core count.
# Usage: scripts/compare/run_comparison.sh [PARTICLES] [STEPS] [REPEATS]   (10000 2000 3)
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
root=$(cd "$here/../.." && pwd)
fibrenet=${FIBRENET:-$root/build/fibrenet}
particles=${1:-10000}
steps=${2:-2000}
repeats=${3:-3}
source "$root/scripts/install_packages.sh"
install_packages lammps esys-particle
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

"$fibrenet" bench --particles "$particles" --steps 1 --write-bed "$work/bed.csv" > /dev/null
read -r -a lammps_vars <<< "$(python3 "$here/bed_to_lammps.py" "$work/bed.csv" "$work/bed.data")"

rate() { python3 -c "print(f'{$1 * $2 / $3 / 1e6:.2f}')"; }
for ((r = 1; r <= repeats; r++)); do
  for threads in 1 2; do
    "$fibrenet" bench --json --particles "$particles" --steps "$steps" --threads "$threads" |
      python3 -c "import json, sys; d = json.load(sys.stdin); \
print(f\"fibrenet  $threads core(s): {d['particle_steps_per_s'] / 1e6:.2f} M particle-steps/s\")"
  done
  for ranks in 1 2; do
    (cd "$work" && mpirun --allow-run-as-root --oversubscribe -np "$ranks" lmp -in \
      "$here/fibre_bed.lammps" "${lammps_vars[@]}" -var steps "$steps" -log none -screen lmp.out)
    wall=$(grep "Loop time" "$work/lmp.out" | tail -1 | awk '{print $4}')
    echo "LAMMPS    $ranks core(s): $(rate "$particles" "$steps" "$wall") M particle-steps/s"
  done
  if command -v esysparticle > /dev/null && [ -f "$here/esys_fibre_bed.py" ]; then
    # One computing worker beside the master (which only waits): one core of work.
    line=$(cd "$work" && mpirun --allow-run-as-root --oversubscribe -np 2 esysparticle \
      "$here/esys_fibre_bed.py" "$work/bed.csv" "$steps" 2> /dev/null | grep "particle-steps/s")
    echo "ESyS      1 core(s): $line"
  fi
done
