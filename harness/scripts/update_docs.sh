#!/usr/bin/env bash
# Rewrites the generated parts of docs/commands.md from the program's tables, after a change to
# renderers/work_counter_list.h: the "Counters" table (between its "<!-- counters: ..." and
# "<!-- end counters -->" lines) and the counters' columns in the CSV table's row of them, from
# `sdfbench backends --counters-markdown table|csv-columns`.
# WorkCounters.DocsListEveryCounterAsTheTableHasIt fails until they are as this writes them.
# Usage: harness/scripts/update_docs.sh [SDFBENCH]   (default: ${BUILD_DIR:-build}/sdfbench, built)
set -euo pipefail
cd "$(dirname "$0")/../.."
bin="${1:-${BUILD_DIR:-build}/sdfbench}"
doc=docs/commands.md
COUNTERS_TABLE="$("$bin" backends --counters-markdown table)"
COUNTERS_CSV="$("$bin" backends --counters-markdown csv-columns)"
export COUNTERS_TABLE COUNTERS_CSV
[[ $(grep -c '^<!-- counters: ' "$doc") == 1 && $(grep -c '^<!-- end counters -->$' "$doc") == 1 ]] ||
  { echo "$doc: needs one '<!-- counters: ...' line and one '<!-- end counters -->' line" >&2; exit 1; }
[[ $(grep -cE '^\| [a-z_]+_per_ray(, [a-z_]+_per_ray)* \| ' "$doc") == 1 ]] ||
  { echo "$doc: needs one CSV table row whose first cell lists the <counter>_per_ray columns" >&2; exit 1; }
tmp="$(mktemp "$doc.XXXXXX")"
trap 'rm -f "$tmp"' EXIT
# The table between the markers, a blank line either side; the row's first cell replaced.
awk '
  /^<!-- end counters -->$/ { inside = 0 }
  inside { next }
  /^<!-- counters: / { print; print ""; print ENVIRON["COUNTERS_TABLE"]; print ""; inside = 1; next }
  /^\| [a-z_]+_per_ray(, [a-z_]+_per_ray)* \| / { $0 = "| " ENVIRON["COUNTERS_CSV"] substr($0, index(substr($0, 3), " | ") + 2) }
  { print }
' "$doc" > "$tmp"
if cmp -s "$tmp" "$doc"; then
  echo "$doc: up to date"
else
  chmod --reference="$doc" "$tmp"
  mv "$tmp" "$doc"
  echo "$doc: counters rewritten"
fi
