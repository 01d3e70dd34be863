#!/usr/bin/env bash
# Lays out every C++ file of the tree by .clang-format (clang-format 14, Debian's).
#   scripts/format.sh          rewrite the files in place
#   scripts/format.sh --check  change nothing; list the files that differ and exit 1 if any does
set -euo pipefail
cd "$(dirname "$0")/.."
format=$(command -v clang-format-14 || command -v clang-format || true)
[[ -n "$format" ]] || { echo "format: clang-format not found (scripts/setup.sh installs it)" >&2; exit 1; }
mapfile -t files < <(git ls-files '*.h' '*.cc')
if [[ "${1:-}" == "--check" ]]; then
  differing=()
  for file in "${files[@]}"; do
    "$format" --style=file "$file" | cmp -s - "$file" || differing+=("$file")
  done
  if [[ ${#differing[@]} -gt 0 ]]; then
    echo "format: ${#differing[@]} of ${#files[@]} files differ from .clang-format (run scripts/format.sh):" >&2
    printf '  %s\n' "${differing[@]}" >&2
    exit 1
  fi
  echo "format: all ${#files[@]} files follow .clang-format"
else
  "$format" --style=file -i "${files[@]}"
fi
