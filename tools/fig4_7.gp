# Thesis Figure 4.7 from the Ronen et al. (2017) fits: δc1/ωc_su, δc2/ωc_su
# and δc2/δc1 versus t/R for Eco/Esu = 2, 4, 6, 8, 10 (ν = 0.32, E/Y = 1000),
# with the thesis's Table 4.2 (computed there from the same fits) as points.
# Usage: gnuplot -e "data='sweep.csv'; table='table4_2.csv'; note='...'; out='fig4_7.png'" tools/fig4_7.gp
# data: `stiction formulas --csv` rows (columns by name); table: the thesis's
# Table 4.2 as printed (data/thesis/table4_2.csv); note: the fits against it.
set terminal pngcairo enhanced size 1500,600 font ",10"
set encoding utf8
set output out
set datafile separator ","
set key autotitle columnheader
set multiplot layout 1,3 margins 0.05,0.99,0.2,0.86 spacing 0.06,0 \
    title "Fig. 4.7: first and second critical interferences of a hard-coated sphere, stick contact, from the Ronen et al. (2017) fits\nν = 0.32, E/Y = 1000 in both layers (normalised by the substrate's ω_{c,su}: the same for any R and E_{su})"
set label 1 note at screen 0.01, screen 0.085
set label 2 "Thin: t/R below (t/R)_{p,st}, outside the range of the stick fits. Points: the thesis's Table 4.2 as printed." at screen 0.01, screen 0.045
set xrange [0:0.05]
set xtics 0.01
set xlabel "t/R  (coating thickness / sphere radius)"
set grid
set key top right Left reverse
ers = "2 4 6 8 10"
# in (thick) and out of (thin) the stick fits' t/R range: flags_stick bit 1
sel(e, col) = (column("E_ratio") == e && (int(column("flags_stick")) & 2) == 0 ? column(col) : 1/0)
out_of_range(e, col) = (column("E_ratio") == e ? column(col) : 1/0)
pt(e, col) = (column("E_ratio") == e ? column(col) : 1/0)
set ylabel "δ_{c1}/ω_{c,su}  (first yield, in the coating; normalised)"
set yrange [0:12]
set title "(a) first yield, in the coating"
plot for [i=1:5] data using "t_over_R":(out_of_range(word(ers,i)+0, "delta_c1_over_omega_c_su")) with lines lw 1 lc i notitle, \
     for [i=1:5] data using "t_over_R":(sel(word(ers,i)+0, "delta_c1_over_omega_c_su")) with lines lw 2.5 lc i title sprintf("E_{co}/E_{su} = %s", word(ers,i)), \
     for [e in "2 4"] table using "t_over_R":(pt(e+0, "delta_c1_over_omega_c_su")) with points pt 7 ps 1.3 lc rgb "black" title (e eq "2" ? "thesis Table 4.2" : "")
set ylabel "δ_{c2}/ω_{c,su}  (second yield, in the substrate; normalised)"
set yrange [0:45]
set title "(b) second yield, in the substrate"
set key top left
plot for [i=1:5] data using "t_over_R":(out_of_range(word(ers,i)+0, "delta_c2_over_omega_c_su")) with lines lw 1 lc i notitle, \
     for [i=1:5] data using "t_over_R":(sel(word(ers,i)+0, "delta_c2_over_omega_c_su")) with lines lw 2.5 lc i title sprintf("E_{co}/E_{su} = %s", word(ers,i)), \
     for [e in "2 4"] table using "t_over_R":(pt(e+0, "delta_c2_over_omega_c_su")) with points pt 7 ps 1.3 lc rgb "black" title (e eq "2" ? "thesis Table 4.2" : "")
set ylabel "δ_{c2}/δ_{c1}"
set yrange [0:45]
set title "(c) ratio (below the line at 1: the substrate yields first)"
set arrow 1 from 0,1 to 0.05,1 nohead lw 2
plot for [i=1:5] data using "t_over_R":(out_of_range(word(ers,i)+0, "delta_c2_over_delta_c1")) with lines lw 1 lc i notitle, \
     for [i=1:5] data using "t_over_R":(sel(word(ers,i)+0, "delta_c2_over_delta_c1")) with lines lw 2.5 lc i title sprintf("E_{co}/E_{su} = %s", word(ers,i))
unset multiplot
