#!/usr/bin/env bash
# One call of the device tool that lends this project an NVIDIA GPU now and then (a machine
# with the NVIDIA driver but no libglvnd, no package access, 64 MiB carried): unpack the
# carried libglvnd packages (.gl/*.deb, see docs/guide/gpu-nodes.md#a-lent-machine) and the
# bundle (build/bundle/ldmbench.tar.xz), check that ldmbench opens the NVIDIA GPU, run the GPU
# suite with nvidia-smi sampling beside it, and leave the records (no images but a few PNGs)
# in $OUT as tarballs under the tool's limits (8 files of 16 MiB). Used for
# docs/measured/gpu-suite.md: run it as `OUT=$OUT bash scripts/gpu-suite-on-device.sh`, carrying
# .gl and build/bundle/ldmbench.tar.xz. SUITE_ARGS replaces the suite's arguments.
set -u
: "${OUT:?}"
exec > >(tee "$OUT/device.log") 2>&1
t0=$(date +%s)
if [ "${LOCAL_TEST:-0}" = 0 ]; then
  for f in .gl/*.deb; do dpkg -x "$f" /; done; ldconfig
fi
echo "== machine"; nvidia-smi 2>&1 | head -20; nproc; head -3 /etc/os-release; ldd --version | head -1
ls /usr/local/nvidia /usr/local/nvidia/share/glvnd/egl_vendor.d /usr/share/glvnd/egl_vendor.d 2>&1 | head -20
rm -rf /tmp/b /tmp/rec; mkdir -p /tmp/b && tar -xJf build/bundle/ldmbench.tar.xz -C /tmp/b || exit 1
B=/tmp/b/ldmbench
want="${WANT_RENDERER:-nvidia}"
info() { timeout 120 "$B/bin/ldmbench" info 2>&1 | tee "$OUT/info.txt"; }
if ! info | grep -q -i "renderer: .*$want"; then
  echo "== retry with the NVIDIA EGL vendor file and library path"
  export __EGL_VENDOR_LIBRARY_FILENAMES=/usr/local/nvidia/share/glvnd/egl_vendor.d/10_nvidia.json
  export LD_LIBRARY_PATH=/usr/local/nvidia/lib64:/usr/local/nvidia/lib:${LD_LIBRARY_PATH:-}
  info | grep -q -i "renderer: .*$want" || { echo "no $want context"; exit 1; }
fi
echo "== setup took $(( $(date +%s) - t0 )) s"
smi_pid=""
if command -v nvidia-smi >/dev/null; then
  nvidia-smi --query-gpu=timestamp,clocks.sm,clocks.mem,power.draw,temperature.gpu,utilization.gpu,clocks_throttle_reasons.active --format=csv -lms 500 > "$OUT/smi.csv" 2>&1 &
  smi_pid=$!
fi
"$B/gpu-suite.sh" --out /tmp/rec ${SUITE_ARGS:-}
rc=$?
[ -n "$smi_pid" ] && kill "$smi_pid"
echo "== suite exit $rc after $(( $(date +%s) - t0 )) s"
export XZ_OPT=-T0
tar -C /tmp/rec -cJf "$OUT/records.tar.xz" --exclude=reference-cache --exclude='*.exr' --exclude='*.png' .
(cd /tmp/rec && find . -path ./*/reference-cache -prune -o \( -name '*-ao.png' -o -name '*-indirect.png' -o -name 'reference-*.png' \) -print) > /tmp/pngs.txt
tar -C /tmp/rec -cf /tmp/images-png.tar -T /tmp/pngs.txt
split -b 15M -d /tmp/images-png.tar "$OUT/images-png.tar.part"
ls "$OUT"/images-png.tar.part* | tail -n +5 | xargs -r rm -f
ls -la "$OUT"; du -sh /tmp/rec/*/* | head -30
echo "== done after $(( $(date +%s) - t0 )) s"
exit $rc
