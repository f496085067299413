"""Reference data of data/ (see data/README.md) for the Python scripts of
make validate / bench / reproduce: each file's rows as dicts of floats (or
of strings where a value is not a number)."""
import csv
import os
import re
import subprocess

DATA = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "data")


def _value(s):
    try:
        return float(s)
    except ValueError:
        return s


def rows(name):
    """The rows of data/NAME (e.g. "thesis/table4_2.csv") as a list of dicts."""
    with open(os.path.join(DATA, name), newline="") as f:
        return [{k: _value(v) for k, v in r.items()} for r in csv.DictReader(f)]


def thesis_table4_1():
    """Thesis Table 4.1 (coated model inputs): parameter -> tuple of values."""
    return {r["parameter"]: tuple(_value(v) for v in str(r["values"]).split())
            for r in rows("thesis/table4_1.csv")}


def binary_version(cli):
    """stiction's version and the commit its binary was built from, as the
    reference files record it ("0.1.0+abc1234", from `stiction --version`:
    "stiction 0.1.0 (commit abc1234)"); "?" for the commit of a binary that
    does not say."""
    p = subprocess.run([cli, "--version"], capture_output=True, text=True)
    m = re.match(r"stiction (\S+)(?: \(commit (\S+)\))?", p.stdout.strip())
    if not m:
        return "?"
    return m.group(1) + "+" + (m.group(2) or "?")
