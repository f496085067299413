# Thesis Figure 4.7 from the Ronen et al. (2017) fits: δc1/ωc_su, δc2/ωc_su
# and δc2/δc1 versus t/R for Eco/Esu = 2, 4, 6, 8, 10 (ν = 0.32, E/Y = 1000).
# Usage: gnuplot -e "data='sweep.csv'; out='fig4_7.png'" tools/fig4_7.gp
# The data are `stiction formulas --csv` rows (columns by name).
set terminal png size 1500,520 font ",11" noenhanced
set output out
set datafile separator ","
set key autotitle columnheader
set multiplot layout 1,3 title "Critical interferences of a hard-coated sphere, stick (Ronen et al. 2017; thesis Fig. 4.7)"
set xrange [0:0.05]
set xtics 0.01
set xlabel "t/R"
set grid
set key top right
ers = "2 4 6 8 10"
sel(e, col) = (column("E_ratio") == e ? column(col) : 1/0)
set ylabel "δc1/ωc_su"
set yrange [0:12]
set title "(a) first yield, in the coating"
plot for [e in ers] data using "t_over_R":(sel(e+0, "delta_c1_over_omega_c_su")) with lines lw 2 title sprintf("Eco/Esu = %s", e)
set ylabel "δc2/ωc_su"
set yrange [0:45]
set title "(b) second yield, in the substrate"
set key top left
plot for [e in ers] data using "t_over_R":(sel(e+0, "delta_c2_over_omega_c_su")) with lines lw 2 title sprintf("Eco/Esu = %s", e)
set ylabel "δc2/δc1"
set yrange [0:45]
set title "(c) ratio (below the line at 1: substrate yields first)"
set arrow 1 from 0,1 to 0.05,1 nohead lw 2
plot for [e in ers] data using "t_over_R":(sel(e+0, "delta_c2_over_delta_c1")) with lines lw 2 title sprintf("Eco/Esu = %s", e)
unset multiplot
