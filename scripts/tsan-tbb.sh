#!/usr/bin/env bash
# Builds oneTBB with ThreadSanitizer and installs it in PREFIX (default build-tsan/onetbb), for
# the ThreadSanitizer build (-DKDRAY_TSAN=ON -DTBB_DIR=PREFIX/lib/cmake/TBB).
# Debian's libtbb.so.12 is not instrumented, so TSan cannot see the synchronisation with which
# it hands a task and its data to a worker and back: every parallel_for, parallel_invoke and
# parallel_sort then looks like a race in the kdray code it runs. Suppressions cannot tell those
# apart from real races (RELIABILITY.md), so the scheduler itself is built with -fsanitize=thread.
# The source is Debian's own package of the installed libtbb-dev version (same upstream release),
# fetched with apt-get from a private deb-src list, so the system's apt configuration is untouched.
# Does nothing when PREFIX already holds that version.
set -euo pipefail
cd "$(dirname "$0")/.."
prefix="$(realpath -m "${1:-build-tsan/onetbb}")"
version="$(dpkg-query -W -f='${Version}' libtbb-dev)"
if [ "$(cat "$prefix/debian-version" 2>/dev/null)" = "$version" ]; then
  exit 0
fi
work="$(realpath -m "$prefix.work")"
rm -rf "$work" "$prefix"
mkdir -p "$work"/apt/lists/partial "$work"/apt/cache/archives/partial "$work"/src
. /etc/os-release
cat >"$work/apt/sources.list" <<EOF
deb-src http://deb.debian.org/debian $VERSION_CODENAME main
deb-src http://deb.debian.org/debian $VERSION_CODENAME-updates main
deb-src http://deb.debian.org/debian-security $VERSION_CODENAME-security main
EOF
apt=(apt-get -q -o Dir::Etc::SourceList="$work/apt/sources.list" -o Dir::Etc::SourceParts=/dev/null
  -o Dir::State::Lists="$work/apt/lists" -o Dir::Cache="$work/apt/cache" -o APT::Sandbox::User=root)
"${apt[@]}" update >/dev/null
(cd "$work" && "${apt[@]}" source --download-only "onetbb=$version" >/dev/null)
tar -xf "$work"/onetbb_*.orig.tar.* -C "$work/src" --strip-components=1
# Only the scheduler library: kdray does not link tbbmalloc. -Wno-tsan: GCC warns, once per
# use in the scheduler, that TSan does not model atomic_thread_fence.
cmake -S "$work/src" -B "$work/build" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_INSTALL_PREFIX="$prefix" \
  -DCMAKE_CXX_FLAGS=-Wno-tsan -DTBB_SANITIZE=thread -DTBB_TEST=OFF -DTBB_STRICT=OFF -DTBBMALLOC_BUILD=OFF \
  -DTBB_DISABLE_HWLOC_AUTOMATIC_SEARCH=ON >/dev/null
cmake --build "$work/build" -j"$(nproc)" >/dev/null
cmake --install "$work/build" >/dev/null
echo "$version" >"$prefix/debian-version"
rm -rf "$work"
