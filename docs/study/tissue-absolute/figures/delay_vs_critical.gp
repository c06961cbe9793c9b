# rupture 0.1.0 (f28c063) plot /tmp/rean5/tissue-absolute
# read: /tmp/rean5/tissue-absolute/results.csv
# Draws delay_vs_critical.png, delay_vs_critical.svg and/or delay_vs_critical.pdf from delay_vs_critical.dat. Rerun in this folder with: gnuplot delay_vs_critical.gp
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
    set output "delay_vs_critical.png"
  }
  if (format eq "svg") {
    set terminal svg size width, height enhanced font font_spec background rgb "white"
    set output "delay_vs_critical.svg"
  }
  if (format eq "pdf") {
    # the page in points as the PNG is in pixels, so that the font keeps its size relative to it
    set terminal pdfcairo size width / 72.0, height / 72.0 enhanced font font_spec
    set output "delay_vs_critical.pdf"
  }
  set title "Delay of failure behind the precursor (6 analysed points)"
  set xlabel "critical strain x_c [%]"
  set ylabel "delay δ_x = x_c - x_p [%]"
  set xrange [0.024657176014206566:0.8829915338343451]
  set yrange [3.0891172754977254e-05:0.8829915338343451]
  set logscale x 10
  set xtics (0.05, 0.1, 0.2, 0.5)
  set format x "%g"
  set logscale y 10
  set ytics autofreq
  set format y "10^{%L}"
  set size noratio
  unset colorbox
  set key tmargin center horizontal box
  unset arrow
  unset label
  plot "delay_vs_critical.dat" index 0 using 1:2:3:4:5:6 with xyerrorbars pointtype 7 pointsize 1.3 linecolor rgb "#1f77b4" title "DEM runs (68 % intervals)", \
    '' index 1 using 1:2 with lines linewidth line_width linecolor rgb "#d62728" title "FBM, α = 0: δ_x = 0.333 x_c", \
    '' index 2 using 1:2 with lines linewidth line_width linecolor rgb "#0000cc" title "FBM, α = 5: δ_x = 0.206 x_c"
  unset output
}
