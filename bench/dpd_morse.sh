#!/usr/bin/env bash
# DPD engine against LAMMPS on one core, like for like: 32,000 copper
# mesoparticles (periodic fcc 20^3 cells, a = 7.23 Å), Morse (shift yes,
# r_c 10 Å, skin 1 Å, neighbour check every step), NVE, dt 0.01 ps, 1,000
# steps from the same 298 K Maxwell–Boltzmann state (dpd_morse_bench writes
# it as a LAMMPS data file with velocities). lmp runs pair_style morse and
# morse/opt, one process, one thread; its rate comes from "Loop time".
# Each time is the best of two runs, and all rates are per processor second
# (lmp: Loop time x its "% CPU use"), so that other jobs on a shared machine
# do not decide the ratios; on an idle machine that is the wall time.
# Prints BENCH dpd_particle_steps_per_s, lammps_morse_particle_steps_per_s,
# lammps_morse_opt_particle_steps_per_s, dpd_vs_lammps_morse (PBMS over the
# faster LAMMPS run, target >= 1.2) and dpd_thermostat_cost (full DPD over
# NVE time, target <= 1.5). Fails when the two codes' initial potential
# energies differ by more than 1e-9 relative: then they run different systems.
set -euo pipefail
ROOT="$1"
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMP_NUM_THREADS=1
work="$(mktemp -d -t pbms-bench.XXXXXX)"
trap 'rm -rf "$work"' EXIT

"$ROOT/build/bin/dpd_morse_bench" "$work" >"$work/pbms.txt"
# Best of two runs each, as dpd_morse_bench takes its times.
for k in 1 2; do
  (cd "$work" && lmp -in in.morse -var pair morse -log "lmp_morse$k.log" -screen none -nocite)
  (cd "$work" && lmp -in in.morse -var pair morse/opt -log "lmp_opt$k.log" -screen none -nocite)
done

awk '
  # The thermo table: header "Step PotEng KinEng TotEng", then one row per
  # output step (0 and the last).
  function read_lmp(file, key,    line, f, n, rows) {
    rows = 0
    delete loop_now
    delete cpu_now
    while ((getline line < file) > 0) {
      n = split(line, f)
      if (f[1] == "Step" && f[2] == "PotEng") { rows = 1; continue }
      if (rows && n == 4 && f[1] ~ /^[0-9]+$/) {
        if (f[1] == 0) { pe0[key] = f[2]; ke0[key] = f[3] } else { pe1[key] = f[2]; ke1[key] = f[3] }
        continue
      }
      rows = 0
      if (f[1] == "Loop" && f[2] == "time") { loop_now[1] = f[4]; steps[key] = f[9]; atoms[key] = f[12] }
      if (f[2] == "CPU" && f[3] == "use") { sub(/%/, "", f[1]); cpu_now[1] = f[1] / 100 }
      if (f[1] == "Neighbor" && f[2] == "list" && f[3] == "builds") builds[key] = f[5]
    }
    close(file)
    if (!(1 in loop_now)) { print "dpd_morse: no Loop time in " file > "/dev/stderr"; exit 1 }
    if (!(1 in cpu_now)) cpu_now[1] = 1
    if (!(key in cpu) || loop_now[1] * cpu_now[1] < cpu[key]) {
      loop[key] = loop_now[1]
      cpu[key] = loop_now[1] * cpu_now[1]
      rate[key] = atoms[key] * steps[key] / cpu[key]
    }
  }
  function abs(x) { return x < 0 ? -x : x }
  FILENAME ~ /pbms.txt$/ {
    if ($1 == "#" && $2 == "pbms" && NF == 4) pbms[$3] = $4
    if ($1 == "BENCH") bench[$2] = $3
    if ($1 == "#") print
    next
  }
  END {
    for (k = 1; k <= 2; ++k) {
      read_lmp(dir "/lmp_morse" k ".log", "morse")
      read_lmp(dir "/lmp_opt" k ".log", "opt")
    }
    split("morse opt", keys)
    for (n = 1; n <= 2; ++n) {
      k = keys[n]
      printf "# lmp %s: cpu %.3f s, wall (Loop time) %.3f s, %d list builds, PE %.15g -> %.15g eV, E_tot %.15g -> %.15g eV\n",
        (k == "opt" ? "morse/opt" : "morse"), cpu[k], loop[k], builds[k], pe0[k], pe1[k],
        pe0[k] + ke0[k], pe1[k] + ke1[k]
    }
    pe_error = abs(pbms["initial_pe"] - pe0["morse"]) / abs(pe0["morse"])
    printf "# initial PE: pbms %.15g eV, lmp %.15g eV, relative difference %.2e\n",
      pbms["initial_pe"], pe0["morse"], pe_error
    printf "# PE after %d steps: pbms %.15g eV, lmp %.15g eV\n", steps["morse"], pbms["final_pe"], pe1["morse"]
    if (!(pe_error < 1e-9)) { print "dpd_morse: PBMS and lmp start from different energies" > "/dev/stderr"; exit 1 }
    faster = rate["morse"] > rate["opt"] ? rate["morse"] : rate["opt"]
    printf "BENCH dpd_particle_steps_per_s %s 1/s\n", bench["dpd_particle_steps_per_s"]
    printf "BENCH lammps_morse_particle_steps_per_s %.4g 1/s\n", rate["morse"]
    printf "BENCH lammps_morse_opt_particle_steps_per_s %.4g 1/s\n", rate["opt"]
    printf "BENCH dpd_vs_lammps_morse %.4f x\n", bench["dpd_particle_steps_per_s"] / faster
    printf "BENCH dpd_thermostat_cost %s x\n", bench["dpd_thermostat_cost"]
  }
' dir="$work" "$work/pbms.txt"
