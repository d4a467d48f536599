#!/usr/bin/env bash
# Every supported Python besides the default one (3.10, 3.12, 3.13; found on PATH as
# python3.X or under pyenv): a fresh virtual environment with the package installed from
# this checkout (not editable), the catalog derived with --out and every generated module
# imported and checked against the published numbers (tools/check_interpreter.py), then a
# fast subset of the tests.  A version this machine lacks is reported and skipped.
# Usage: tools/check_pythons.sh [VERSION ...]   (default: 3.10 3.11 3.12 3.13)
set -euo pipefail
cd "$(dirname "$0")/.."
root=$PWD
default=$(python3 -c 'import sys; print(f"{sys.version_info[0]}.{sys.version_info[1]}")')
fast_tests=(tests/test_code_layout.py tests/test_api_values.py tests/test_exit_statuses.py tests/test_one_contract.py tests/test_atlas_enumeration.py)
status=0
versions=("$@")
[ ${#versions[@]} -gt 0 ] || versions=(3.10 3.11 3.12 3.13)
for version in "${versions[@]}"; do
    [ "$version" = "$default" ] && continue
    # pyenv's own folders first (its shims answer for versions that are not selected), then PATH.
    python=$(ls -d "${PYENV_ROOT:-$HOME/.pyenv}"/versions/"$version".*/bin/python"$version" 2>/dev/null | sort -V | tail -n 1 || true)
    [ -n "$python" ] || python=$(command -v "python$version" || true)
    if [ -z "$python" ] || ! "$python" -c 'import sys' >/dev/null 2>&1; then
        echo "check_pythons: Python $version not found on this machine; skipped" >&2
        continue
    fi
    work=$(mktemp -d)
    echo "check_pythons: Python $version ($python)"
    "$python" -m venv "$work/venv"
    "$work/venv/bin/python" -m pip install --quiet --disable-pip-version-check "$root" pytest pytest-xdist hypothesis 2>&1 \
        | grep -v -e '^WARNING: Location' -e 'Running pip as the' || true
    # The tests import the installed package, not the checkout's (run from the work folder).
    cp -r "$root/tests" "$root/catalog" "$root/derivations" "$root/tools" "$root/pyproject.toml" "$work/"
    if ! "$work/venv/bin/python" "$root/tools/check_interpreter.py" "$root" "$work/out"; then status=1; fi
    if ! (cd "$work" && "$work/venv/bin/python" -m pytest -q -p no:cacheprovider -n 2 "${fast_tests[@]}"); then status=1; fi
    rm -rf "$work"
done
exit $status
