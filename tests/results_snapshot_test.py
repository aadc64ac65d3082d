#!/usr/bin/python3
"""The committed snapshot (issue 40): every CSV of results/<device>/ (not results/history/) holds
rows of one commit, measured from a clean tree (no "-dirty"), and the README's findings are the
figures of those CSVs (harness/scripts/findings.py --check).

    tests/results_snapshot_test.py [REPO]   (default: the repository this file is in)
"""
import csv
import glob
import os
import subprocess
import sys

repo = sys.argv[1] if len(sys.argv) > 1 else os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
failures = []
folders = [d for d in glob.glob(os.path.join(repo, "results", "*")) if os.path.isdir(d) and os.path.basename(d) != "history"]
if not folders:
    failures.append("no device folder under results/")
for folder in folders:
    commits = {}
    files = glob.glob(os.path.join(folder, "**", "*.csv"), recursive=True)
    if not files:
        failures.append(f"{folder}: no CSV")
    for path in files:
        with open(path, newline="") as f:
            for n, row in enumerate(csv.DictReader(f), start=2):
                commit = row.get("commit", "")
                commits.setdefault(commit, f"{os.path.relpath(path, repo)} line {n}")
    for commit, where in commits.items():
        if not commit or commit.endswith("-dirty"):
            failures.append(f"{where}: commit '{commit}' is not a clean commit")
    if len(commits) > 1:
        failures.append(f"{os.path.relpath(folder, repo)}: rows of {len(commits)} commits: " +
                        ", ".join(f"{c} ({w})" for c, w in commits.items()))
    print(f"results_snapshot_test: {os.path.relpath(folder, repo)}: {len(files)} CSVs, commits {sorted(commits)}")
check = subprocess.run([sys.executable, os.path.join(repo, "harness", "scripts", "findings.py"), "--results",
                        os.path.join(repo, "results", "lavapipe"), "--check", os.path.join(repo, "README.md")],
                       capture_output=True, text=True)
print(check.stdout.strip())
if check.returncode != 0:
    failures.append(check.stderr.strip())
for f in failures:
    print(f"results_snapshot_test: FAIL: {f}", file=sys.stderr)
sys.exit(1 if failures else 0)
