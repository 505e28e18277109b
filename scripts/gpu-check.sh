#!/usr/bin/env bash
# The GPU back end on a real GPU, in a few minutes (issue 10): the drawing, parity, shadow and edit tests
# on the hardware adapter, then the benchmark on the paper's workload (10,000 strands, 40 SRBF lights,
# 720 x 480, single + multiple scattering) on the GPU and, for a same-run ratio, on the CPU.
# Results land in out/gpu-check/: adapters.txt, tests.log, bench-gpu/ and bench-cpu/bench.json.
#
#   bash scripts/gpu-check.sh              # builds, then runs (needs crates.io or a warm target/)
#   bash scripts/gpu-check.sh --prebuilt D # runs binaries built elsewhere and copied into D:
#                                          #   D/cuticle, D/drawing, D/parity, D/shadows,
#                                          #   D/edits
#                                          #   (see --stage)
#   bash scripts/gpu-check.sh --stage D    # on a machine that can build: build and copy them to D
#
# A machine lent for this without network cannot fetch crates: stage the binaries on the build
# machine (about 60 MB, small enough to carry) and run them there with --prebuilt.
# `--device gpu` takes the best adapter, hardware before software; bench.json's "device" and
# the tests' adapter line name the one it took. wgpu needs a Vulkan driver for an NVIDIA GPU
# (the ICD of the NVIDIA driver, libnvidia-gl): without one it falls back to lavapipe, which
# this script reports and treats as a failure.
set -euo pipefail
cd "$(dirname "$0")/.."
out=out/gpu-check
mode=${1:-build}
dir=${2:-}

stage() {
    cargo build --release -p cuticle
    local tests
    tests=$(cargo test --release -p cuticle-gpu --no-run --message-format=json 2>/dev/null |
        grep -o '"executable":"[^"]*"' | cut -d'"' -f4)
    mkdir -p "$1"
    cp target/release/cuticle "$1/"
    for t in $tests; do
        case $(basename "$t") in
        drawing-*) cp "$t" "$1/drawing" ;;
        parity-*) cp "$t" "$1/parity" ;;
        edits-*) cp "$t" "$1/edits" ;;
        shadows-*) cp "$t" "$1/shadows" ;;
        esac
    done
    ls -la "$1"
}

case $mode in
--stage)
    stage "$dir"
    exit 0
    ;;
--prebuilt) bin=$dir ;;
*)
    bin=target/gpu-check-bin
    stage "$bin" >/dev/null
    ;;
esac

mkdir -p "$out"
if command -v vulkaninfo >/dev/null; then
    vulkaninfo --summary 2>/dev/null | grep -E "deviceName|deviceType" | tee "$out/adapters.txt" || true
    if ! grep -q -E "DISCRETE_GPU|INTEGRATED_GPU|VIRTUAL_GPU" "$out/adapters.txt"; then
        echo "gpu-check: no hardware Vulkan adapter (only software or none): install the GPU's Vulkan driver" >&2
        exit 1
    fi
fi

# Parity (GPU against CPU drawings, images and shadow maps, the bounds of crates/gpu/tests) and
# edit tests (passes counted).
{ "$bin/drawing" --nocapture --test-threads 1 && "$bin/parity" --nocapture --test-threads 1 &&
    "$bin/shadows" --nocapture --test-threads 1 && "$bin/edits" --nocapture --test-threads 1; } 2>&1 |
    tee "$out/tests.log" |
    grep -E "subsamples covered|to the side|relative RMSE|moves this image|shadows|unfiltered|test result|panicked|FAILED"

"$bin/cuticle" bench render --device gpu --strands 10000 --frames 5 --out "$out/bench-gpu"
"$bin/cuticle" bench render --device cpu --strands 10000 --frames 1 --out "$out/bench-cpu"
grep -A3 '"adapter"' "$out/bench-gpu/bench.json" | head -4
echo "gpu-check: done; figures in $out/bench-gpu/bench.json and $out/bench-cpu/bench.json"
