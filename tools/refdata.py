"""Reference data of data/ (see data/README.md) for the Python scripts of
make validate / bench / reproduce: each file's rows as dicts of floats (or
of strings where a value is not a number)."""
import csv
import os

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
