#!/usr/bin/env bash
# The README fits on a screen and every relative link in it and in docs/, results/ and scenes/
# resolves to a file of the checkout (issue 30): a moved page or a renamed result breaks this test.
set -euo pipefail
cd "$(dirname "$0")/.."
fail() { echo "docs_links_test: FAIL: $*" >&2; exit 1; }
lines=$(wc -l <README.md)
((lines <= 150)) || fail "README.md has $lines lines (at most 150: the reference belongs in docs/)"
checked=0
for page in README.md docs/*.md results/README.md scenes/README.md; do
  dir=$(dirname "$page")
  # Markdown links [text](target): not URLs, not in-page anchors; the anchor part is dropped.
  while IFS= read -r target; do
    path=${target%%#*}
    [[ -z $path ]] && continue
    [[ -e $dir/$path ]] || fail "$page links to '$target', which does not exist"
    checked=$((checked + 1))
  done < <(grep -o '\]([^)[:space:]]*)' "$page" | sed 's/^](//; s/)$//' | grep -v -E '^(https?:|mailto:|#)' || true)
done
((checked >= 20)) || fail "only $checked links found: the link extraction is broken"
echo "docs_links_test: $checked links resolve; README.md has $lines lines"
