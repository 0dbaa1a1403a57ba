#!/usr/bin/env bash
# Fails when a Catch2 test name would be run as something else by ctest. catch_discover_tests passes each name
# to the test executable as a test spec, through a CMake list: a ';' splits the name into several tests that
# each match nothing, an unbalanced '[' opens a tag, and a name that starts with '-' is read as an option. Catch2 2
# exits 0 when a spec matches nothing, so such a test case would silently never run (or, as an unknown option,
# fail without running). Usage: check_test_names.sh TEST_EXECUTABLE...
set -uo pipefail
bad=0
for exe in "$@"; do
  while IFS= read -r name; do
    open=${name//[^\[]/}
    close=${name//[^\]]/}
    if [[ $name == *";"* || ${#open} -ne ${#close} || $name == -* ]]; then
      echo "$(basename "$exe"): \"$name\": no ';', only balanced [ ] and no leading '-' in test names (ctest would not run it)"
      bad=1
    fi
  done < <("$exe" --list-test-names-only)
done
exit $bad
