"""What the figures of make reproduce share: gnuplot runs that write a PNG
atomically, the text conventions of a figure (gnuplot enhanced text: _{..}
subscripts, Greek letters as UTF-8) and the deviation of a result from its
reference written the same way on every plot.

Every figure says on itself what it shows: a title with the case (material,
t/R, Eco/Esu, contact condition, model), axes with units or marked as
normalised, the reference curve where the thesis or a published fit gives
one, and the deviation from it."""
import os
import subprocess
import sys

# the terminal of every figure: PNG drawn by cairo (dashed reference lines),
# enhanced text (subscripts), UTF-8
TERMINAL = "set terminal pngcairo enhanced size %d,%d font ',10'\nset encoding utf8\n"

# symbols in gnuplot enhanced text
OMEGA_C = "ω_{c}"
OMEGA_C_SU = "ω_{c,su}"
P_C_SU = "P_{c,su}"
MU_S = "μ_{s}"


def gnuplot(png, width, height, script):
    """Run script (without terminal and output lines) into png via png.tmp
    and a rename, so a reader never sees half a figure."""
    head = TERMINAL % (width, height) + "set output '%s.tmp'\n" % png
    p = subprocess.run(["gnuplot"], input=head + script, capture_output=True, text=True)
    if p.returncode != 0:
        raise RuntimeError("gnuplot failed for %s: %s" % (png, p.stderr.strip()))
    os.replace(png + ".tmp", png)


def number(fig):
    """The thesis's figure number of a figure name: 'fig4_19' -> '4.19'."""
    return fig[3:].replace("_", ".")


def pct(x):
    """A relative deviation as a signed percentage, e.g. -0.0912 -> '−9.1 %'."""
    return ("%+.1f %%" % (100.0 * x)).replace("-", "−")


def pct_range(devs):
    """'−14.2 … −8.9 %' for a list of relative deviations (one value: '−8.9 %')."""
    devs = sorted(d for d in devs if d == d)
    if not devs:
        return "n/a"
    if len(devs) == 1 or "%.1f" % (100 * devs[0]) == "%.1f" % (100 * devs[-1]):
        return pct(devs[0])
    return "%s … %s" % (pct(devs[0])[:-2], pct(devs[-1]))


def label(text, x, y, where="graph", extra=""):
    """A gnuplot label line at (x, y) in graph (0..1) or screen coordinates."""
    return "set label \"%s\" at %s %g, %s %g %s\n" % (text, where, x, where, y, extra)


LINE_PX = 20  # one line of notes at font size 11


def notes(lines, height):
    """Notes under the plot(s) of a figure height pixels tall, one label a
    line at the bottom left: (script, bottom), bottom the screen fraction
    above them that holds the x tics and label, where the plot area may
    start (set bmargin at screen bottom, or a multiplot's margins)."""
    s = "".join(label(t, 0.01, (len(lines) - i - 0.3) * LINE_PX / height, "screen")
                for i, t in enumerate(lines))
    return s, (len(lines) * LINE_PX + 48.0) / height


def quote(s):
    """s inside a gnuplot double-quoted enhanced-text string: backslashes
    and quotes escaped, underscores and carets printed as themselves."""
    s = s.replace("\\", "\\\\").replace('"', '\\"')
    for c in "_^@&~{}":
        s = s.replace(c, "\\\\" + c)
    return s


class _Tee:
    def __init__(self, a, b):
        self.a, self.b = a, b

    def write(self, s):
        self.a.write(s)
        self.b.write(s)

    def flush(self):
        self.a.flush()
        self.b.flush()


def tee_stdout(path):
    """From now on, what the script prints goes to path as well (the summary
    kept beside a figure)."""
    sys.stdout = _Tee(sys.stdout, open(path, "w"))
