# rupture 0.1.0 (f28c063) plot /tmp/rean5/small-relative
# read: /tmp/rean5/small-relative/results.csv
# Draws mechanism_map.png, mechanism_map.svg and/or mechanism_map.pdf from mechanism_map.dat. Rerun in this folder with: gnuplot mechanism_map.gp
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
    set output "mechanism_map.png"
  }
  if (format eq "svg") {
    set terminal svg size width, height enhanced font font_spec background rgb "white"
    set output "mechanism_map.svg"
  }
  if (format eq "pdf") {
    # the page in points as the PNG is in pixels, so that the font keeps its size relative to it
    set terminal pdfcairo size width / 72.0, height / 72.0 enhanced font font_spec
    set output "mechanism_map.pdf"
  }
  set title "Breaking mechanisms over the scan (49 points)"
  set xlabel "bond stiffness k_n [N/mm]"
  set ylabel "breaking distance b_d [mm]"
  set xrange [5:20000]
  set yrange [0.0005:1]
  set logscale x 10
  set xtics autofreq
  set format x "10^{%L}"
  set logscale y 10
  set ytics autofreq
  set format y "10^{%L}"
  set size noratio
  unset colorbox
  set key tmargin center horizontal box
  unset arrow
  unset label
  plot "mechanism_map.dat" index 0 using 1:2 with points pointtype 7 pointsize 2 linecolor rgb "#1f77b4" title "brittle", \
    '' index 1 using 1:2 with points pointtype 7 pointsize 2 linecolor rgb "#d62728" title "hyper-elastic", \
    '' index 2 using 1:2 with points pointtype 7 pointsize 2 linecolor rgb "#2ca02c" title "semi-ductile", \
    '' index 3 using 1:2 with points pointtype 2 pointsize 2 linecolor rgb "#555555" title "rejected: peaks not resolved", \
    '' index 4 using 1:2 with points pointtype 6 pointsize 1.5 linecolor rgb "#aaaaaa" title "not separated, failed or not run"
  unset output
}
