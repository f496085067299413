"""One part of the validation report (make validate): markdown with three kinds
of rows, kept apart on purpose.

check    a measured value against a verified reference: a closed form, the
         same model's mesh-converged answer, or an independent code.  A failed
         check fails `make validate`.
compare  a measured value against a published fit.  A fit is a regression of
         someone's data, not a reference: a disagreement beyond the stated
         tolerance becomes a *finding*, written with its numbers and the
         independent evidence that decides which side is off.
target   an accuracy goal the project has set itself and does not meet yet,
         stated with the measured value so the gap stays visible.

The last line of the file sums them up; tools/validate-report.py reads it to
build docs/validation.md.
"""
import os
import time

SUMMARY = "summary:"


class Report:
    def __init__(self, title, source):
        """title: the part's heading; source: the script and CLI runs behind it."""
        self.lines = ["# %s" % title, "",
                      "Generated %s by %s." % (time.strftime("%Y-%m-%d"), source), ""]
        self.checks = self.failed = 0
        self.findings = []
        self.targets = self.unmet = 0
        self._table = None

    def out(self, s=""):
        self._end_table()
        print(s, flush=True)
        self.lines.append(s)

    def _row(self, kind, cells):
        if self._table != kind:
            self._end_table()
            head = {"check": ("check", "reference (source)", "tolerance", "measured", "verdict"),
                    "compare": ("comparison", "published fit", "tolerance", "measured",
                                "verdict"),
                    "target": ("target", "goal", "measured", "verdict")}[kind]
            self.lines += ["| " + " | ".join(head) + " |", "|" + "---|" * len(head)]
            self._table = kind
        s = "| " + " | ".join(str(c) for c in cells) + " |"
        print(s, flush=True)
        self.lines.append(s)

    def _end_table(self):
        if self._table:
            self.lines.append("")
            self._table = None

    def check(self, name, reference, tolerance, measured, ok):
        self.checks += 1
        self.failed += not ok
        self._row("check", (name, reference, tolerance, measured, "pass" if ok else "FAIL"))
        return ok

    def compare(self, name, fit, tolerance, measured, agrees, finding=None):
        """finding: (title, evidence) written under Findings when the fit disagrees."""
        verdict = "agrees"
        if not agrees:
            self.findings.append((name, fit, measured) + (finding or ("", "")))
            verdict = "finding F%d" % len(self.findings)
        self._row("compare", (name, fit, tolerance, measured, verdict))

    def target(self, name, goal, measured, met):
        self.targets += 1
        self.unmet += not met
        self._row("target", (name, goal, measured, "met" if met else "not met yet"))

    def write(self, path):
        self._end_table()
        if self.findings:
            self.lines += ["## Findings: where a published fit and the FE disagree", ""]
            for k, (name, fit, measured, title, evidence) in enumerate(self.findings, 1):
                self.lines += ["**F%d. %s** (%s; fit %s)%s" % (k, name, measured, fit,
                                                               (": " + title) if title else ""),
                               "", evidence, ""]
        self.lines.append("%s %d checks, %d failed; %d findings; %d targets, %d not met yet"
                          % (SUMMARY, self.checks, self.failed, len(self.findings),
                             self.targets, self.unmet))
        with open(path + ".tmp", "w") as f:
            f.write("\n".join(self.lines) + "\n")
        os.replace(path + ".tmp", path)
        return 0 if self.failed == 0 else 1
