#!/usr/bin/env bash
# The GPU back end on a real GPU, in a few minutes (issue 10): build, the parity and edit
# tests on the hardware adapter, then the benchmark on the paper's workload (10,000 strands,
# 40 SRBF lights, 720 x 480, single + multiple scattering) on the GPU and, for the same-run
# ratio, on the CPU. Results land in out/gpu-check/ (bench.json of each, the test log).
#
#   bash scripts/gpu-check.sh            # from the repository root
#
# Needs a Vulkan (or Metal/DX12) driver for the GPU; `--device gpu` takes the best adapter,
# hardware before software, and bench.json's "device" names the one it took.
set -euo pipefail
cd "$(dirname "$0")/.."
out=out/gpu-check
mkdir -p "$out"
command -v vulkaninfo >/dev/null && vulkaninfo --summary 2>/dev/null | grep -E "deviceName|deviceType" | tee "$out/adapters.txt" || true

cargo build --release -p cuticle -p cuticle-gpu --tests 2>&1 | tail -3
# Parity (GPU against CPU images, the thresholds of crates/gpu/tests) and edit tests on this
# machine's best adapter.
cargo test --release -p cuticle-gpu -- --nocapture 2>&1 | tee "$out/tests.log" | grep -E "relative RMSE|test result|panicked|FAILED"

bin=target/release/cuticle
$bin bench render --device gpu --strands 10000 --frames 5 --out "$out/bench-gpu"
$bin bench render --device cpu --strands 10000 --frames 1 --out "$out/bench-cpu"
echo "bench.json: $out/bench-gpu/bench.json, $out/bench-cpu/bench.json"
