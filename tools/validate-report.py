#!/usr/bin/env python3
"""Assemble the validation report, docs/validation.md, from the parts that
`make validate` writes into RESULTS_DIR (validate-*.md, tools/vreport.py).

validate-report.py RESULTS_DIR OUT.md

A part that was not run this time (make validate ONLY=...) keeps its section
and its summary row from the report already at OUT.md, if that has it, and is
listed as not run otherwise; each part's own date says when it ran.
"""
import os
import re
import subprocess
import sys

from vreport import SUMMARY

PARTS = [("install", "Installed library"), ("asperity", "Asperity FE solver"),
         ("surface", "Surface layer"), ("shear", "Combined loading (WSP sphere)"),
         ("references", "One shear run against the converged references"),
         ("growth", "Junction growth (half-space)"),
         ("smoothness", "Smoothness along the interference"), ("stress", "Numerical stability"),
         ("tables", "FE friction tables")]


def summary(text):
    for line in reversed(text.splitlines()):
        if line.startswith(SUMMARY):
            m = re.findall(r"(\d+)", line)
            return [int(x) for x in m]  # checks, failed, findings, targets, unmet
    return None


def main():
    res, out = sys.argv[1], sys.argv[2]
    version = subprocess.run(["git", "describe", "--always", "--dirty"], capture_output=True,
                             text=True).stdout.strip() or "unknown"
    rows, body, carried = [], [], []
    kept = earlier(out)
    for key, title in PARTS:
        path = os.path.join(res, "validate-%s.md" % key)
        if not os.path.exists(path):
            if title in kept:
                row, section = kept[title]
                rows.append(row)
                body += section + ([] if section[-1] == "" else ["", ""])
                carried.append(title)
            else:
                rows.append("| %s | not run | | | |" % title)
            continue
        text = open(path).read()
        s = summary(text)
        if s and len(s) == 5:
            rows.append("| [%s](#%s) | %d | %d | %d | %d |" % (title, anchor(text), s[0], s[1],
                                                              s[2], s[4]))
        else:
            rows.append("| %s | (no summary) | | | |" % title)
        for line in text.rstrip().splitlines():
            if line.startswith(SUMMARY):
                continue
            body.append("#" + line if line.startswith("#") else line)
        body.append("")
    kept_note = (" Not run this time and kept from the previous report, each with its own "
                 "date: %s." % ", ".join(carried) if carried else "")
    head = ["# Validation report", "",
            "Written by `make validate` (tools/validate-report.py) from the parts in "
            "`results/`; source tree %s.%s Three kinds of rows, kept apart:"
            % (version, kept_note), "",
            "* **check**: a measured value against a verified reference (a closed form, the "
            "same model's mesh-converged answer, an independent code). A failed check fails "
            "`make validate`.",
            "* **comparison**: a measured value against a published fit. A fit is a regression "
            "of someone's data, not a reference; a disagreement beyond the stated tolerance is "
            "a *finding*, given with its numbers and the evidence that decides it.",
            "* **target**: an accuracy goal not met yet, with the measured value.", "",
            "| part | checks | failed | findings | targets not met |", "|---|---|---|---|---|"]
    head += rows
    with open(out + ".tmp", "w") as f:
        f.write("\n".join(head + [""] + body).rstrip() + "\n")
    os.replace(out + ".tmp", out)
    print("wrote %s" % out)


def earlier(path):
    """The parts of the report already at PATH: title -> (its summary row, the
    lines of its section), for the parts that row links to a section."""
    if not os.path.exists(path):
        return {}
    lines = open(path).read().rstrip().splitlines()
    sections, cur = {}, None
    for line in lines:
        if line.startswith("## "):
            cur = anchor(line[1:])
            sections[cur] = []
        if cur is not None:
            sections[cur].append(line)
    kept = {}
    for line in lines:
        m = re.match(r"\| \[(.+?)\]\(#(.+?)\) \|", line)
        if m and m.group(2) in sections:
            kept[m.group(1)] = (line, sections[m.group(2)])
    return kept


def anchor(text):
    """GitHub's anchor of the part's first heading."""
    h = text.splitlines()[0].lstrip("#").strip().lower()
    return re.sub(r"[^a-z0-9 _-]", "", h).replace(" ", "-")


if __name__ == "__main__":
    main()
