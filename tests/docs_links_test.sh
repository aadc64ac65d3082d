#!/usr/bin/env bash
# The README fits on a screen and every relative link in it and in docs/, results/ and scenes/
# resolves to a file of the checkout (issue 30): a moved page or a renamed result breaks this test.
# So does every source path named in the docs' text or the code's comments ("renderers/tri_aabb/tri_aabb.comp",
# issue 57): a file moved into a backend's folder leaves no stale pointer behind.
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
named=0
pattern='(renderers|harness|util|scenes|tests|docs|cmake)/[A-Za-z0-9_/.-]+\.(h|cpp|comp|glsl|rgen|rchit|rmiss|md|sh|cmake)'
while IFS= read -r hit; do
  path=${hit#*:*:}
  [[ -e $path ]] || fail "${hit%:*} names '$path', which does not exist"
  named=$((named + 1))
done < <(git grep -n -o -E "$pattern" -- ':!results/*/*' || true)
((named >= 500)) || fail "only $named source paths found: the path extraction is broken"
echo "docs_links_test: $checked links and $named named source paths resolve; README.md has $lines lines"
