# rupture 0.1.0 (f28c063) plot /tmp/rean5/small-absolute
# read: /tmp/rean5/small-absolute/results.csv
# Draws energy_ratio_vs_critical.png, energy_ratio_vs_critical.svg and/or energy_ratio_vs_critical.pdf from energy_ratio_vs_critical.dat. Rerun in this folder with: gnuplot energy_ratio_vs_critical.gp
# Restyle here: sizes, fonts, line width and colours; the formats drawn are listed in `formats`.
formats = "png svg pdf"
width = 1000
height = 700
font_spec = "Sans,14"
line_width = 2
bond_width = 1  # snapshots: line width of a bond
bond_palette = "defined (0 '#3b4cc0', 0.5 '#8c8c8c', 1 '#b40426')"  # snapshots: compressed - unstretched (grey, visible on white) - stretched
marker_color = "#555555"

set datafile missing "?"
set grid
set tics out
set style textbox opaque noborder  # marker labels stay readable over the curves

do for [format in formats] {
  if (format eq "png") {
    # pngcairo draws antialiased text; the plain libgd png terminal is the fallback
    if (strstrt(GPVAL_TERMINALS, "pngcairo") > 0) {
      set terminal pngcairo size width, height enhanced font font_spec
    } else {
      set terminal png size width, height enhanced font font_spec
    }
    set output "energy_ratio_vs_critical.png"
  }
  if (format eq "svg") {
    set terminal svg size width, height enhanced font font_spec background rgb "white"
    set output "energy_ratio_vs_critical.svg"
  }
  if (format eq "pdf") {
    # the page in points as the PNG is in pixels, so that the font keeps its size relative to it
    set terminal pdfcairo size width / 72.0, height / 72.0 enhanced font font_spec
    set output "energy_ratio_vs_critical.pdf"
  }
  set title "Energy ratio A_r against critical strain (36 analysed points)"
  set xlabel "critical strain x_c [%]"
  set ylabel "A_r = E_{max} / (x_p ℰ_{max}) [1]"
  set xrange [0.026432982478712227:61.36993850127925]
  set yrange [0:1.7249999999999999]
  set logscale x 10
  set xtics autofreq
  set format x "10^{%L}"
  unset logscale y
  set ytics autofreq
  set format y "% h"
  set size noratio
  unset colorbox
  set key tmargin center horizontal box
  unset arrow
  unset label
  plot "energy_ratio_vs_critical.dat" index 0 using 1:2:3:4:5:6 with xyerrorbars pointtype 7 pointsize 1.5 linecolor rgb "#1f77b4" title "Γ < 1", \
    '' index 1 using 1:2 with lines linewidth line_width linecolor rgb "#d62728" title "FBM, α = 0: A_r = 1.333", \
    '' index 2 using 1:2 with lines linewidth line_width linecolor rgb "#0000cc" title "FBM, α = 5: A_r = 0.837"
  unset output
}
