#!/bin/sh
# The coated and the uncoated surface predictions side by side: a table on
# stdout and a PNG.  Usage: demo-compare.sh COATED.csv UNCOATED.csv OUT.png
# (gw.csv files of `stiction surface predict --table`, same pressures).
set -eu
C=$1
U=$2
PNG=$3
join_rows() {
    awk -F, '
        FNR == 1 { f++ }
        /^#/ { next }
        !hdr[f]++ { for (i = 1; i <= NF; i++) col[f, $i] = i; next }
        f == 1 { n++; p[n] = $col[1, "nominal_pressure_MPa"]
                 mc[n] = $col[1, "mu_s"]; ec[n] = $col[1, "mu_s_err"]
                 ac[n] = $col[1, "A_over_An"]; oc[n] = $col[1, "load_fraction_outside_model_range"] }
        f == 2 { m++; mu[m] = $col[2, "mu_s"]; eu[m] = $col[2, "mu_s_err"]
                 au[m] = $col[2, "A_over_An"]; ou[m] = $col[2, "load_fraction_outside_model_range"]
                 if ($col[2, "nominal_pressure_MPa"] != p[m]) { print "pressures differ" > "/dev/stderr"; exit 1 } }
        END { for (i = 1; i <= n; i++)
                  printf "%s %s %s %s %s %s %s %s %s\n", p[i], mc[i], ec[i], ac[i], oc[i],
                         mu[i], eu[i], au[i], ou[i] }' "$C" "$U"
}
rows=$(join_rows)
echo "   P/An        mu_s coated       mu_s uncoated     A/An coated   A/An uncoated   outside"
echo "   [MPa]       (TiN 1.5 um)      (steel)                                         c / u"
echo "$rows" | awk '{ printf "%7g    %6.3f +- %5.3f    %6.3f +- %5.3f    %.3e     %.3e      %.2f / %.2f\n",
                       $1, $2, $3, $6, $7, $4, $8, $5, $9 }'
echo "  (+- one standard error from the tables; outside: share of the load beyond a table's range)"
dat=$(mktemp)
trap 'rm -f "$dat"' EXIT
echo "$rows" > "$dat"
# coated over bare, the figure's message, written on it
ratio=$(echo "$rows" | awk '{ r = $2 / $6; if (NR == 1 || r < lo) lo = r; if (NR == 1 || r > hi) hi = r }
                            END { printf "%.2f … %.2f", lo, hi }')
gnuplot > /dev/null 2>&1 <<GP
set terminal pngcairo enhanced size 1300,560 font ",10"
set encoding utf8
set output "$PNG.tmp"
set multiplot layout 1,2 margins 0.06,0.98,0.17,0.84 spacing 0.08,0 title "Ground hardened steel (RMS 0.4 μm, 1 × 1 mm map), 1.5 μm TiN coating versus bare: Greenwood-Williamson sums over the map's summits\nasperity response from the FE friction tables tin-on-steel.h5 (TiN: E = 400 GPa, Y = 7 GPa on steel) and steel.h5 (steel: E = 200 GPa, Y = 1.5 GPa, ν = 0.3)"
set label 1 "Coated over bare μ_{s}: ${ratio}. Bands: ± 1 standard error of the tables' surrogates. No published reference exists for these surfaces." at screen 0.01, screen 0.03
set logscale x
set grid
set xlabel "nominal pressure P/A_{n} [MPa]"
set ylabel "static friction coefficient μ_{s} = ΣQ_{max}/ΣP"
set key top right
set title "static friction coefficient"
plot "$dat" using 1:(\$2-\$3):(\$2+\$3) with filledcurves fs transparent solid 0.25 lc rgb "#c04000" notitle, \
     "" using 1:2 with linespoints lw 2 pt 7 lc rgb "#c04000" title "TiN 1.5 μm on steel", \
     "" using 1:(\$6-\$7):(\$6+\$7) with filledcurves fs transparent solid 0.25 lc rgb "#0050a0" notitle, \
     "" using 1:6 with linespoints lw 2 pt 5 lc rgb "#0050a0" title "bare steel"
unset label 1
set logscale y
set ylabel "real contact area fraction A/A_{n}"
set key top left
set title "real contact area"
plot "$dat" using 1:4 with linespoints lw 2 pt 7 lc rgb "#c04000" title "TiN 1.5 μm on steel", \
     "" using 1:8 with linespoints lw 2 pt 5 lc rgb "#0050a0" title "bare steel"
unset multiplot
GP
mv "$PNG.tmp" "$PNG"
