#!/usr/bin/env bash
# The report in a real browser (issue 30): a small table with kept images, its `sdfbench report`
# opened in headless Chromium (Debian's chromium package; install_deps.sh installs it). A probe
# (a copy of the page with a script added; the page itself has none) waits for the load and
# writes into the DOM what it found: every image decoded (naturalWidth > 0) and each row's three
# image links. Console messages fail the test. A control page with one image removed must be
# caught, so the probe cannot pass by seeing nothing. A screenshot is left for a person to look at.
# Usage: report_browser_test.sh SDFBENCH_BINARY SCREENSHOT.png
set -euo pipefail
sdfbench="$1"
screenshot="$2"
chromium="$(command -v chromium || true)"
if [ -z "$chromium" ]; then
  echo "report_browser_test: chromium is not installed (harness/scripts/install_deps.sh installs Debian's chromium)" >&2
  exit 1
fi
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT

"$sdfbench" table --table 6.3 --meshes sphere --objects 1,10 --backends embree,tri-aabb,bvh --size 64x36 --check-size 64x36 \
  --frames 1 --warmup 0 --csv "$work/t.csv" --keep-images "$work/kept" >"$work/table.log" 2>&1 ||
  { cat "$work/table.log"; exit 1; }
"$sdfbench" report "$work/t.csv" --out "$work/report.html"

browser() {
  # --no-sandbox: CI runs as root; the profile is the test's own, so nothing of a user's is read.
  "$chromium" --headless --no-sandbox --disable-gpu --disable-dev-shm-usage --user-data-dir="$work/profile" \
    --enable-logging=stderr --v=0 "$@"
}

cat >"$work/probe.js" <<'PROBE'
window.addEventListener("load", () => {
  const images = [...document.images];
  const broken = images.filter(i => !(i.complete && i.naturalWidth > 0)).map(i => i.getAttribute("src"));
  const rows = [...document.querySelectorAll("table.rows tr[id]")];
  const unlinked = rows.filter(r => r.querySelectorAll("td.images a[href$=\".png\"] img").length !== 3).map(r => r.id);
  const out = document.createElement("pre");
  out.textContent = "PROBE images=" + images.length + " broken=" + broken.length + " rows=" + rows.length +
    " unlinked=" + unlinked.length + " :" + broken.concat(unlinked).join(" ");
  document.body.appendChild(out);
});
PROBE

# Runs the probe on page $1; prints its result line; the browser's stderr goes to $2.
run_probe() {
  local page="$1" log="$2" copy
  copy="$(dirname "$page")/probe-$(basename "$page")"
  [ "$(dirname "$page")" = "$work" ] || cp "$work/probe.js" "$(dirname "$page")/"
  sed 's|</body>|<script src="probe.js"></script></body>|' "$page" >"$copy"
  browser --virtual-time-budget=15000 --dump-dom "file://$copy" 2>"$log" | grep -o 'PROBE [^<]*' || true
}

result="$(run_probe "$work/report.html" "$work/browser.log")"
echo "report: $result"
rows="$(sed -n 's/.* rows=\([0-9]*\) .*/\1/p' <<<"$result")"
images="$(sed -n 's/.*PROBE images=\([0-9]*\) .*/\1/p' <<<"$result")"
fail=0
[ "$rows" = "6" ] || { echo "expected the table's 6 rows on the page, found '${rows:-none}'" >&2; fail=1; }
[ "$images" = "18" ] || { echo "expected 18 images (3 per row), found '${images:-none}'" >&2; fail=1; }
grep -q ' broken=0 ' <<<"$result" || { echo "images that did not decode: $result" >&2; fail=1; }
grep -q ' unlinked=0 ' <<<"$result" || { echo "rows without their three image links: $result" >&2; fail=1; }
if grep -q 'CONSOLE' "$work/browser.log"; then
  echo "console messages:" >&2
  grep 'CONSOLE' "$work/browser.log" >&2
  fail=1
fi
# Every link on the page leads to a file beside it.
while read -r target; do
  [ -f "$work/$target" ] || { echo "the page links '$target', which is not there" >&2; fail=1; }
done < <(grep -o 'href="report_files/[^"]*"' "$work/report.html" | sed 's/^href="//; s/"$//' | sort -u)

# The control: the same page with one image gone must be caught.
mkdir "$work/control"
cp -r "$work/report.html" "$work/report_files" "$work/control/"
rm "$(ls "$work/control/report_files/"*.png | sed -n 1p)"
control="$(run_probe "$work/control/report.html" "$work/control.log")"
echo "control (one image removed): $control"
if grep -q ' broken=0 ' <<<"$control" || [ -z "$control" ]; then
  echo "the probe did not notice a missing image: it would not catch a broken page" >&2
  fail=1
fi

# The console check can fail: a copy of the page whose script logs must show in the log.
sed 's|</body>|<script>console.error("sdfbench-console-control")</script></body>|' "$work/report.html" >"$work/console.html"
run_probe "$work/console.html" "$work/console.log" >/dev/null
if ! grep 'CONSOLE' "$work/console.log" | grep -q 'sdfbench-console-control'; then
  echo "a page that logs to the console left no CONSOLE line: the console check would not catch one" >&2
  fail=1
fi

browser --screenshot="$screenshot" --window-size=1280,1600 "file://$work/report.html" >/dev/null 2>&1
[ -s "$screenshot" ] || { echo "no screenshot was written" >&2; fail=1; }
[ "$fail" = 0 ] && echo "report_browser_test: ok (screenshot: $screenshot)"
exit "$fail"
