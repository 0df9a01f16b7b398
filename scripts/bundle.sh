#!/usr/bin/env bash
# Makes a relocatable bundle of ldmbench for GPU nodes without package access
# (docs/guide/gpu-nodes.md): the binaries, the GPU-only test binaries scripts/gpu-suite.sh
# runs, the scene files and sweeps with the models they reference, every shared library they
# load except the GPU driver's and the C library's, launchers, and the suite.
#
#   scripts/bundle.sh [OUT] [--build DIR] [--no-build] [--tar]
#
# OUT (default build/bundle/ldmbench) is replaced. Libraries find each other through
# RUNPATH $ORIGIN (patchelf), so a binary works from any path, also when ldmbench runs
# itself again (--isolation process). Libraries larger than 4 MiB (Embree, Assimp) are kept
# xz-compressed under lib/packed/ to keep the folder under 60 MiB; the launchers unpack them
# into lib/ on first use (the folder must then be writable). --tar also writes OUT.tar.xz.
# Shaders are compiled into the binaries; nothing is read from this source tree at run time
# except by `ldmbench report`, which needs Python and is not bundled (run it at home).
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
out="$root/build/bundle/ldmbench"
build="$root/build"
do_build=1
do_tar=0
while [ $# -gt 0 ]; do
  case "$1" in
    --build) build="$(cd "${2:?--build needs a folder}" 2>/dev/null && pwd)" ||
               { echo "bundle.sh: --build '$2' is not a folder" >&2; exit 2; }
             shift 2 ;;
    --no-build) do_build=0; shift ;;
    --tar) do_tar=1; shift ;;
    -h|--help) sed -n '2,15p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
    -*) echo "bundle.sh: unknown option '$1' (see --help)" >&2; exit 2 ;;
    *) out="$1"; shift ;;
  esac
done
case "$out" in /*) ;; *) out="$PWD/$out" ;; esac

# The limit the folder must stay under (the device tool carries 64 MiB; clusters' home
# quotas are often small); the packed libraries are what makes it fit.
limit_mib=60
pack_over_bytes=$((4 << 20))

programs=(ldmbench ldmbench_gbench)
tests=(test_structures test_context)  # the suites scripts/gpu-suite.sh runs on the GPU
for tool in patchelf strip xz ldd; do
  command -v "$tool" >/dev/null || { echo "bundle.sh: '$tool' is missing (scripts/setup.sh installs it)" >&2; exit 1; }
done

if [ "$do_build" = 1 ]; then
  [ -f "$build/CMakeCache.txt" ] || cmake -S "$root" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release
  cmake --build "$build" --target "${programs[@]}" "${tests[@]}"
fi
for p in "${programs[@]}"; do [ -x "$build/$p" ] || { echo "bundle.sh: $build/$p is not built" >&2; exit 1; }; done
for t in "${tests[@]}"; do [ -x "$build/tests/$t" ] || { echo "bundle.sh: $build/tests/$t is not built" >&2; exit 1; }; done

# Libraries that stay the node's: the GPU driver's (libglvnd's dispatch and the vendor's
# EGL/GL, Mesa's drivers on a machine without a GPU) and the C library, which must match the
# node's kernel and the driver's own libraries. tests/bundle/check-bundle.sh uses this list.
node_lib_pattern='^(libEGL|libGL|libGLX|libGLdispatch|libOpenGL|libGLESv[12]_CM|libGLESv2|libnvidia|libcuda|libdrm|libgbm|libglapi|libc|libm|libdl|libpthread|librt|libutil|libresolv|ld-linux)[-.]'

tmp="$out.tmp.$$"
rm -rf "$tmp"
trap 'rm -rf "$tmp"' EXIT
mkdir -p "$tmp/libexec/tests" "$tmp/lib/packed" "$tmp/bin"

cp "${programs[@]/#/$build/}" "$tmp/libexec/"
for t in "${tests[@]}"; do cp "$build/tests/$t" "$tmp/libexec/tests/"; done

# Every library the binaries load, resolved on this machine, minus the node's own.
mapfile -t libraries < <(
  for f in "$tmp"/libexec/* "$tmp"/libexec/tests/*; do
    [ -f "$f" ] && ldd "$f" | awk '/=> \// { print $1 " " $3 }'
  done | sort -u | while read -r name path; do
    [[ "$name" =~ $node_lib_pattern ]] || echo "$path"
  done | sort -u)
for path in "${libraries[@]}"; do
  cp -L "$path" "$tmp/lib/$(basename "$path")"
done

# Strip (the Debian libraries are stripped already; ours are not) and point every object at
# the bundle's lib/.
for f in "$tmp"/libexec/* "$tmp"/libexec/tests/* "$tmp"/lib/*.so*; do
  [ -f "$f" ] || continue
  chmod u+w "$f"
  strip --strip-unneeded "$f"
done
for f in "$tmp"/libexec/*; do [ -f "$f" ] && patchelf --set-rpath '$ORIGIN/../lib' "$f"; done
for f in "$tmp"/libexec/tests/*; do patchelf --set-rpath '$ORIGIN/../../lib' "$f"; done
for f in "$tmp"/lib/*.so*; do patchelf --set-rpath '$ORIGIN' "$f"; done

# The largest libraries travel compressed; the launchers unpack them on first use.
for f in "$tmp"/lib/*.so*; do
  if [ "$(stat -c %s "$f")" -gt "$pack_over_bytes" ]; then
    xz -T0 -6 -c "$f" > "$tmp/lib/packed/$(basename "$f").xz"
    rm "$f"
  fi
done

# Scenes, sweeps and the models they reference. Scene files that name an installed model
# (/usr/share/assimp/models/...) get the model beside them and a relative path to it; the
# scene's identity (and so its configuration ids) then differs from the source tree's.
cp -r "$root/scenes" "$root/sweeps" "$tmp/"
rm -f "$tmp/scenes/meshes/"*.py
mkdir -p "$tmp/scenes/models"
for scene in "$tmp"/scenes/*.json; do
  for model in $(grep -o '"/usr/share/assimp/models/[^"]*"' "$scene" | tr -d '"'); do
    if [ ! -f "$model" ]; then
      echo "bundle.sh: $(basename "$scene") references $model, which is not installed (assimp-testmodels; scripts/setup.sh)" >&2
      exit 1
    fi
    cp "$model" "$tmp/scenes/models/"
    sed -i "s|\"$model\"|\"models/$(basename "$model")\"|" "$scene"
  done
done

# Launchers: bin/NAME unpacks what is packed, then runs libexec/NAME.
cat > "$tmp/libexec/bundle-env.sh" <<'EOF'
# Sourced by the launchers in bin/: the bundle's root, and the packed libraries unpacked.
bundle_root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
export LDM_BUNDLE_DIR="$bundle_root"
for packed in "$bundle_root"/lib/packed/*.xz; do
  [ -e "$packed" ] || continue
  lib="$bundle_root/lib/$(basename "$packed" .xz)"
  [ -f "$lib" ] && continue
  if ! command -v xz >/dev/null; then
    echo "ldmbench bundle: xz is needed once, to unpack $(basename "$packed") into $bundle_root/lib" >&2
    exit 1
  fi
  if ! xz -dc "$packed" > "$lib.tmp.$$" || ! chmod 755 "$lib.tmp.$$" || ! mv -f "$lib.tmp.$$" "$lib"; then
    rm -f "$lib.tmp.$$"
    echo "ldmbench bundle: cannot unpack $packed into $bundle_root/lib (copy the bundle to a writable folder)" >&2
    exit 1
  fi
done
EOF
glibc_needed="$(for f in "$tmp"/libexec/* "$tmp"/libexec/tests/* "$tmp"/lib/*.so*; do
  [ -f "$f" ] && objdump -T "$f" 2>/dev/null; done | grep -o 'GLIBC_[0-9.]*' | sort -uV | tail -1 | sed 's/GLIBC_//')"
cat >> "$tmp/libexec/bundle-env.sh" <<EOF
# The newest C library symbol version the bundled objects use (the C library is the node's).
glibc_needed="$glibc_needed"
EOF
cat >> "$tmp/libexec/bundle-env.sh" <<'EOF'
glibc_here="$(getconf GNU_LIBC_VERSION 2>/dev/null | awk '{print $2}')"
if [ -n "$glibc_here" ] && [ "$(printf '%s\n%s\n' "$glibc_needed" "$glibc_here" | sort -V | head -1)" != "$glibc_needed" ]; then
  echo "ldmbench bundle: this node's C library is glibc $glibc_here; the bundle needs $glibc_needed or newer (build it on an older system, docs/guide/gpu-nodes.md)" >&2
  exit 1
fi
EOF
for name in "${programs[@]}" "${tests[@]}"; do
  target="libexec/$name"
  case " ${tests[*]} " in *" $name "*) target="libexec/tests/$name" ;; esac
  cat > "$tmp/bin/$name" <<EOF
#!/usr/bin/env bash
# Launcher of the ldmbench bundle: unpacks the packed libraries once, then runs $target.
source "\$(dirname "\$(readlink -f "\${BASH_SOURCE[0]}")")/../libexec/bundle-env.sh"
exec "\$bundle_root/$target" "\$@"
EOF
  chmod 755 "$tmp/bin/$name"
done
cp "$root/scripts/gpu-suite.sh" "$tmp/gpu-suite.sh"
chmod 755 "$tmp/gpu-suite.sh"

# What is inside, for the records' provenance and for whoever opens the folder.
{
  echo "ldmbench bundle"
  echo "commit: $(git -C "$root" rev-parse HEAD 2>/dev/null || echo unknown)$(git -C "$root" diff --quiet HEAD 2>/dev/null || echo ' (with uncommitted changes)')"
  echo "built: $(date -u +%Y-%m-%dT%H:%M:%SZ) on $(. /etc/os-release 2>/dev/null && echo "$PRETTY_NAME")"
  echo "needs: x86-64, glibc >= $glibc_needed, an OpenGL 4.5 driver with EGL (libEGL.so.1, libOpenGL.so.0: the node's), bash, xz (once)"
  echo "run: bin/ldmbench info; ./gpu-suite.sh [--out DIR] (docs/guide/gpu-nodes.md)"
  echo "libraries (lib/, lib/packed/ compressed):"
  (cd "$tmp/lib" && ls -1 *.so* packed/*.xz 2>/dev/null | sed 's/^/  /')
} > "$tmp/MANIFEST.txt"

size_bytes="$(du -sb "$tmp" | cut -f1)"
if [ "$size_bytes" -gt $((limit_mib << 20)) ]; then
  echo "bundle.sh: the bundle is $((size_bytes >> 20)) MiB, over the $limit_mib MiB limit" >&2
  exit 1
fi
rm -rf "$out"
mkdir -p "$(dirname "$out")"
mv "$tmp" "$out"
trap - EXIT
unpacked="$(for p in "$out"/lib/packed/*.xz; do xz --robot --list "$p"; done |
  awk -v n="$size_bytes" '$1 == "totals" { n += $5 - $4 } END { printf "%d", n }')"
echo "bundle: $out ($((size_bytes * 10 / 1048576 / 10)).$((size_bytes * 10 / 1048576 % 10)) MiB; $((unpacked >> 20)) MiB once its packed libraries are unpacked; ${#libraries[@]} libraries; needs glibc >= $glibc_needed)"
if [ "$do_tar" = 1 ]; then
  XZ_OPT="${XZ_OPT:--T0}" tar -C "$(dirname "$out")" -cJf "$out.tar.xz" "$(basename "$out")"
  echo "bundle: $out.tar.xz ($(( $(stat -c %s "$out.tar.xz") >> 20 )) MiB)"
fi
