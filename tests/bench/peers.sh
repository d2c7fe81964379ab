#!/usr/bin/env bash
# Whole processes of iblbake beside Filament's cmgen and cmft (issue 18 item 5; a benchmark, not a test).
# The peers are built by ../shared/peers/ into $PEERS_DIR/bin; an absent peer is skipped with a message.
# Each round runs every tool once, in turn (iblbake, cmgen, cmft), so load drifting on a shared machine
# reaches them all alike; after one untimed warm-up round (page cache, PoCL's compiled-kernel cache),
# RUNS rounds are timed and each tool's median wall-clock time is printed with the ratio iblbake/peer.
# Every run starts in a fresh empty directory, so nothing a run writes is seen by the next one.
#
# Jobs (1k lat-long input, 256-texel faces, 9 levels: 256 x 256 down to 1 x 1):
#   chain  the GGX LD chain. iblbake `specular` production (256 samples per texel before its per-lobe
#          rules, bright texels integrated exactly), KTX2 rgba16f; cmgen 1,024 samples, KTX1 R11G11B10;
#          cmft Phong lobes (no GGX), KTX1 rgba32f (command lines of ../shared/peers/README.md).
#   dfg    the DFG LUT 128 x 128, 1,024 samples, OpenEXR. iblbake also bakes the Disney diffuse channel;
#          cmft has no DFG LUT.
#   sh     SH of the map from a 256-texel cube. iblbake `diffuse` (L2, windowed, JSON); cmgen --sh=3 (L2,
#          printed); cmft shcoeffs (L4, 25 coefficients, a C header).
#   batch  the seven HDRIs of ../shared/data/hdri: one `iblbake batch` of HDRI items (per item the LD
#          chain, L2 SH and the sun check; one DFG LUT for all) over a fresh `--cache` per run, so it is
#          cache-cold; the peers one process after another: cmgen the DFG LUT once, then per HDRI its LD
#          chain and SH in one process; cmft per HDRI its radiance chain and its SH (two processes).
#          The peers read Radiance files only (cmgen also some OpenEXR files): every other input is given
#          to them as RGB float .hdr converted by oiiotool before timing, the cube strip as a vertical
#          cross for cmgen (which reads no strips).
#
# Usage: tests/bench/peers.sh   (env: IBLBAKE=build/cli/iblbake PEERS_DIR=/tmp/iblbake-peers RUNS=5
#        HDRI=<1k lat-long> BACKEND=auto|opencl|cpu JOBS="chain dfg sh batch")
set -euo pipefail
export LC_ALL=C # EPOCHREALTIME and printf with a '.' decimal point
root=$(cd "$(dirname "$0")/../.." && pwd)
iblbake=${IBLBAKE:-$root/build/cli/iblbake}
peers_bin=${PEERS_DIR:-${TMPDIR:-/tmp}/iblbake-peers}/bin
runs=${RUNS:-5}
hdri_dir=$root/../shared/data/hdri
hdri=${HDRI:-$hdri_dir/rooitou_park_1k.hdr}
backend=${BACKEND:-auto}
jobs=${JOBS:-chain dfg sh batch}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

[ -x "$iblbake" ] || { echo "peers.sh: $iblbake: not built (cmake --build build --target iblbake iblbake-engine)" >&2; exit 1; }
tools=(iblbake)
for peer in cmgen cmft; do
  if [ -x "$peers_bin/$peer" ]; then tools+=("$peer"); else
    echo "peers.sh: $peer: skipped, $peers_bin/$peer not found (build it with ../shared/peers/build-$peer.sh)" >&2
  fi
done

# --- the jobs: <job>_<tool> runs one whole job in the current (empty) directory -----------------------
cmft_radiance() { # $1 input, $2 output name
  "$peers_bin/cmft" --input "$1" --filter radiance --srcFaceSize 256 --dstFaceSize 256 --excludeBase false \
    --mipCount 9 --glossScale 10 --glossBias 1 --lightingModel phongbrdf --edgeFixup none \
    --numCpuProcessingThreads 2 --useOpenCL false --generateMipChain false --outputNum 1 --output0 "$2" \
    --output0params ktx,rgba32f,cubemap
}
cmft_sh() { "$peers_bin/cmft" --input "$1" --filter shcoeffs --srcFaceSize 256 --outputNum 1 --output0 "$2"; }

chain_iblbake() { "$iblbake" specular "$hdri" -o ld.ktx2 --size 256 --backend "$backend"; }
chain_cmgen() { mkdir ld && "$peers_bin/cmgen" -q --format=ktx --size=256 --ibl-min-lod-size=1 --ibl-ld=ld "$hdri"; }
chain_cmft() { cmft_radiance "$hdri" ld; }
dfg_iblbake() { "$iblbake" dfg -o dfg.exr --size 128 --samples 1024 --backend "$backend"; }
dfg_cmgen() { "$peers_bin/cmgen" -q --size=128 --ibl-dfg=dfg.exr; }
sh_iblbake() { "$iblbake" diffuse "$hdri" -o sh.json --size 256 --backend "$backend"; }
sh_cmgen() { "$peers_bin/cmgen" --size=256 --sh=3 "$hdri"; }
sh_cmft() { cmft_sh "$hdri" sh; }
batch_iblbake() {
  cp "$work/batch.json" . && "$iblbake" batch batch.json --cache cache --quiet --backend "$backend"
}
batch_cmgen() {
  "$peers_bin/cmgen" -q --size=128 --ibl-dfg=dfg.exr
  for input in "$work"/cmgen-input/*.hdr; do
    local name
    name=$(basename "$input" .hdr)
    mkdir "$name" && "$peers_bin/cmgen" -q --format=ktx --size=256 --ibl-min-lod-size=1 --ibl-ld="$name" \
      --sh=3 --sh-output="$name/sh.txt" "$input"
  done
}
batch_cmft() {
  for input in "$work"/hdr-input/*.hdr; do
    cmft_radiance "$input" "$(basename "$input" .hdr)" && cmft_sh "$input" "$(basename "$input" .hdr)_sh"
  done
}

# The batch's inputs, prepared before any timing: iblbake's manifest of the originals, the peers' .hdr files.
prepare_batch() {
  mkdir "$work/hdr-input" "$work/cmgen-input"
  local items=() input name
  for input in "$hdri_dir"/*.exr "$hdri_dir"/*.hdr; do
    name=$(basename "${input%.*}")
    items+=("{\"hdri\": \"$input\"}")
    case $input in
    *.hdr) cp "$input" "$work/hdr-input/" ;;
    *) oiiotool "$input" --fullpixels --ch R,G,B -d float -o "$work/hdr-input/$name.hdr" ;;
    esac
    cp "$work/hdr-input/$name.hdr" "$work/cmgen-input/"
  done
  (IFS=,; echo "{\"items\": [${items[*]}]}") >"$work/batch.json"
  # A vertical strip (+X -X +Y -Y +Z -Z) becomes a vertical cross (. +Y . / -X +Z +X / . -Y . / . -Z .)
  # for cmgen, -Z turned 180 degrees as docs/conventions.md "Lat-long mapping and pixel placement" lays out a cross.
  local strip cell cells
  for strip in "$work"/cmgen-input/*.hdr; do
    oiiotool --info "$strip" | grep -q ': *256 x 1536,' || continue
    cells=()
    for cell in - 2 - 1 4 0 - 3 - - 5 -; do # strip face index per cross cell, row by row; - is black
      if [ "$cell" = - ]; then cells+=(--pattern "constant:color=0,0,0" 256x256 3); else
        cells+=("$strip" --cut "256x256+0+$((cell * 256))")
        [ "$cell" = 5 ] && cells+=(--rotate180)
      fi
    done
    oiiotool "${cells[@]}" --mosaic 3x4 -o "$strip.cross.hdr" && mv "$strip.cross.hdr" "$strip"
  done
}

# Wall-clock seconds of one run of "$1" in a fresh directory; a failed run stops the benchmark.
time_run() {
  local dir start end
  dir=$(mktemp -d "$work/run.XXXXXX")
  start=$EPOCHREALTIME
  if ! (cd "$dir" && "$1" >"$work/log" 2>&1); then
    echo "peers.sh: $1 failed:" >&2
    tail -5 "$work/log" >&2
    exit 1
  fi
  end=$EPOCHREALTIME
  rm -rf "$dir"
  awk -v s="$start" -v e="$end" 'BEGIN { printf "%.3f\n", e - s }'
}

median() { sort -g | awk '{ v[NR] = $1 } END { print (NR % 2 ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2) }'; }

echo "date: $(date -u '+%Y-%m-%d %H:%M UTC'); cpu: $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2- | xargs), $(nproc) cores"
echo "iblbake: $("$iblbake" --version), --backend $backend; runs: $runs (+1 warm-up), alternating"
echo "load before: $(uptime)"
header="| job | iblbake (s)"
for peer in "${tools[@]:1}"; do header+=" | $peer (s) | iblbake/$peer"; done
rows=()
for job in $jobs; do
  [ "$job" = batch ] && prepare_batch
  present=()
  for tool in "${tools[@]}"; do declare -F "${job}_$tool" >/dev/null && present+=("$tool"); done
  for tool in "${present[@]}"; do : >"$work/$job.$tool"; done
  for round in $(seq 0 "$runs"); do # round 0 is the warm-up
    for tool in "${present[@]}"; do
      seconds=$(time_run "${job}_$tool")
      [ "$round" = 0 ] || echo "$seconds" >>"$work/$job.$tool"
    done
  done
  ours=$(median <"$work/$job.iblbake")
  row="| $job | $ours"
  for peer in "${tools[@]:1}"; do
    if [ -s "$work/$job.$peer" ]; then
      theirs=$(median <"$work/$job.$peer")
      row+=" | $theirs | $(awk -v a="$ours" -v b="$theirs" 'BEGIN { printf "%.2f", a / b }')"
    else
      row+=" | - | -"
    fi
  done
  rows+=("$row |")
  for tool in "${present[@]}"; do echo "$job, $tool, seconds: $(paste -sd' ' "$work/$job.$tool")"; done
done
echo "load after: $(uptime)"
echo
echo "$header |"
echo "|---$(for _ in "${tools[@]:1}"; do printf '|---|---'; done)|---|"
printf '%s\n' "${rows[@]}"
