#!/usr/bin/env bash
# README's package command run exactly as README gives it, from a fresh
# build folder (issue 34: CI packaged its own full build tree, so it never
# saw that board/package.sh's own build left candela-studio out and CPack
# aborted). Then what each .deb must hold: the kiosk's programs in candela,
# the offline tools (and the studio, where libimgui-dev is installed) in
# candela-tool.
#   tests/package/readme_package.sh      (from anywhere; about a Release build's time)
set -euo pipefail
cd "$(dirname "$0")/../.."
grep -q '^    board/package.sh ' README.md ||
  { echo "readme_package: README no longer gives 'board/package.sh' as a command" >&2; exit 1; }
rm -rf build-package out/deb
board/package.sh
status=0
has() {  # PACKAGE FILE
  local deb
  deb=$(ls out/deb/"$1"_*.deb 2>/dev/null | head -1)
  if [ -z "$deb" ]; then echo "readme_package: FAIL no $1 .deb in out/deb"; status=1; return; fi
  local files
  files=$(dpkg-deb -c "$deb")
  if grep -q " \./$2\$" <<<"$files"; then echo "readme_package: ok   $1 has /$2"
  else echo "readme_package: FAIL $1 lacks /$2"; status=1; fi
}
has candela usr/bin/candela
has candela usr/bin/candela-record
has candela etc/candela/candela.toml
has candela-tool usr/bin/candela-tool
if grep -q '^CANDELA_STUDIO:INTERNAL=ON' build-package/CMakeCache.txt; then
  has candela-tool usr/bin/candela-studio
fi
exit $status
