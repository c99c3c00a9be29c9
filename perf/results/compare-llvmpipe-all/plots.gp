# dirt-compare's figures: gnuplot /tmp/cmpall/plots.gp (data: NAME.dat)

# memory_vs_triangles
reset
set terminal svg noenhanced size 720,632 font 'sans,9' background '#ffffff'
set for [i=1:8] linetype i lc rgb word('#0072b2 #d55e00 #009e73 #cc79a7 #e69f00 #56b4e9 #999999 #882255', i) lw 1.3
set output '/tmp/cmpall/memory_vs_triangles.svg'
set multiplot title 'Structure memory vs the scenes'' triangles (log), per image size'
unset border
unset tics
set xrange [0:1]
set yrange [0:1]
set key center center horizontal maxcols 3 samplen 2.5 reverse Left width 1 noautotitle
set origin 0,0.895570
set size 1,0.050633
set lmargin 0
set rmargin 0
set tmargin 0
set bmargin 0
plot NaN w lp lc 1 dt 1 pt 7 ps 0.8 t 'DIRT S1', NaN w lp lc 3 dt 1 pt 6 ps 0.8 t 'DIRT S2', NaN w lp lc 2 dt 1 pt 5 ps 0.8 t 'MMRT'
set border
set tics
set key off
set grid
set autoscale
set autoscale fix
unset lmargin
unset rmargin
unset tmargin
unset bmargin
set offsets graph 0.08, graph 0.08, graph 0.08, graph 0.08
set format y '%g'
set logscale x
set logscale y
set xtics ('default (1478)' 1478, 'CornellBox.glb (36) / CornellBox-Original.obj (36)' 36, 'cornell_box.glb (4410)' 4410, 'AnimatedMorphCube.gltf (12)' 12, 'AnimatedTriangle.gltf (1)' 1, 'BoxAnimated.gltf (254)' 254, 'CesiumMan.glb (4672)' 4672, 'CesiumMilkTruck.gltf (3624)' 3624, 'FlightHelmet.gltf (94722)' 94722, 'Fox.glb (576)' 576, 'MorphStressTest.gltf (2412)' 2412, 'RiggedFigure.gltf (256)' 256, 'RiggedSimple.gltf (188)' 188, 'SimpleSkin.gltf (8)' 8) rotate by 90 right font ',8'
set origin 0.000000,0.000000
set size 1.000000,0.895570
set title '256x128'
set ylabel 'used MB (log)'
set xlabel ''
set bmargin at screen 0.509494
set ytics ('1' 1, '2' 2, '5' 5, '10' 10, '20' 20)
plot '/tmp/cmpall/memory_vs_triangles.dat' index 0 u ($1+0.0000):2:3:4 w lp lc 1 dt 1 pt 7 ps 0.8 notitle, '/tmp/cmpall/memory_vs_triangles.dat' index 1 u ($1+0.0000):2:3:4 w lp lc 2 dt 1 pt 5 ps 0.8 notitle, '/tmp/cmpall/memory_vs_triangles.dat' index 2 u ($1+0.0000):2:3:4 w lp lc 3 dt 1 pt 6 ps 0.8 notitle
unset multiplot
set output

# memory_vs_triangles
reset
set terminal pngcairo noenhanced size 720,632 font 'sans,9'
set for [i=1:8] linetype i lc rgb word('#0072b2 #d55e00 #009e73 #cc79a7 #e69f00 #56b4e9 #999999 #882255', i) lw 1.3
set output '/tmp/cmpall/memory_vs_triangles.png'
set multiplot title 'Structure memory vs the scenes'' triangles (log), per image size'
unset border
unset tics
set xrange [0:1]
set yrange [0:1]
set key center center horizontal maxcols 3 samplen 2.5 reverse Left width 1 noautotitle
set origin 0,0.895570
set size 1,0.050633
set lmargin 0
set rmargin 0
set tmargin 0
set bmargin 0
plot NaN w lp lc 1 dt 1 pt 7 ps 0.8 t 'DIRT S1', NaN w lp lc 3 dt 1 pt 6 ps 0.8 t 'DIRT S2', NaN w lp lc 2 dt 1 pt 5 ps 0.8 t 'MMRT'
set border
set tics
set key off
set grid
set autoscale
set autoscale fix
unset lmargin
unset rmargin
unset tmargin
unset bmargin
set offsets graph 0.08, graph 0.08, graph 0.08, graph 0.08
set format y '%g'
set logscale x
set logscale y
set xtics ('default (1478)' 1478, 'CornellBox.glb (36) / CornellBox-Original.obj (36)' 36, 'cornell_box.glb (4410)' 4410, 'AnimatedMorphCube.gltf (12)' 12, 'AnimatedTriangle.gltf (1)' 1, 'BoxAnimated.gltf (254)' 254, 'CesiumMan.glb (4672)' 4672, 'CesiumMilkTruck.gltf (3624)' 3624, 'FlightHelmet.gltf (94722)' 94722, 'Fox.glb (576)' 576, 'MorphStressTest.gltf (2412)' 2412, 'RiggedFigure.gltf (256)' 256, 'RiggedSimple.gltf (188)' 188, 'SimpleSkin.gltf (8)' 8) rotate by 90 right font ',8'
set origin 0.000000,0.000000
set size 1.000000,0.895570
set title '256x128'
set ylabel 'used MB (log)'
set xlabel ''
set bmargin at screen 0.509494
set ytics ('1' 1, '2' 2, '5' 5, '10' 10, '20' 20)
plot '/tmp/cmpall/memory_vs_triangles.dat' index 0 u ($1+0.0000):2:3:4 w lp lc 1 dt 1 pt 7 ps 0.8 notitle, '/tmp/cmpall/memory_vs_triangles.dat' index 1 u ($1+0.0000):2:3:4 w lp lc 2 dt 1 pt 5 ps 0.8 notitle, '/tmp/cmpall/memory_vs_triangles.dat' index 2 u ($1+0.0000):2:3:4 w lp lc 3 dt 1 pt 6 ps 0.8 notitle
unset multiplot
set output

# time_vs_triangles
reset
set terminal svg noenhanced size 1020,632 font 'sans,9' background '#ffffff'
set for [i=1:8] linetype i lc rgb word('#0072b2 #d55e00 #009e73 #cc79a7 #e69f00 #56b4e9 #999999 #882255', i) lw 1.3
set output '/tmp/cmpall/time_vs_triangles.svg'
set multiplot title 'Times vs the scenes'' triangles (log), per image size: the build, the trace passes, the whole frame (medians; bars: min-max of the repeats)'
unset border
unset tics
set xrange [0:1]
set yrange [0:1]
set key center center horizontal maxcols 3 samplen 2.5 reverse Left width 1 noautotitle
set origin 0,0.895570
set size 1,0.050633
set lmargin 0
set rmargin 0
set tmargin 0
set bmargin 0
plot NaN w lp lc 1 dt 1 pt 7 ps 0.8 t 'DIRT S1', NaN w lp lc 3 dt 1 pt 6 ps 0.8 t 'DIRT S2', NaN w lp lc 2 dt 1 pt 5 ps 0.8 t 'MMRT th default (0.2 %)'
set border
set tics
set key off
set grid
set autoscale
set autoscale fix
unset lmargin
unset rmargin
unset tmargin
unset bmargin
set offsets graph 0.08, graph 0.08, graph 0.08, graph 0.08
set format y '%g'
set logscale x
set logscale y
set xtics ('default (1478)' 1478, 'CornellBox.glb (36) / CornellBox-Original.obj (36)' 36, 'cornell_box.glb (4410)' 4410, 'AnimatedMorphCube.gltf (12)' 12, 'AnimatedTriangle.gltf (1)' 1, 'BoxAnimated.gltf (254)' 254, 'CesiumMan.glb (4672)' 4672, 'CesiumMilkTruck.gltf (3624)' 3624, 'FlightHelmet.gltf (94722)' 94722, 'Fox.glb (576)' 576, 'MorphStressTest.gltf (2412)' 2412, 'RiggedFigure.gltf (256)' 256, 'RiggedSimple.gltf (188)' 188, 'SimpleSkin.gltf (8)' 8) rotate by 90 right font ',8'
set origin 0.000000,0.000000
set size 0.333333,0.895570
set title '256x128: build'
set ylabel 'ms (log)'
set xlabel ''
set bmargin at screen 0.509494
set ytics ('1' 1, '10' 10, '100' 100)
plot '/tmp/cmpall/time_vs_triangles.dat' index 0 u ($1+0.0000):2:3:4 w yerrorlines lc 1 dt 1 pt 7 ps 0.8 notitle, '/tmp/cmpall/time_vs_triangles.dat' index 1 u ($1+0.0000):2:3:4 w yerrorlines lc 2 dt 1 pt 5 ps 0.8 notitle, '/tmp/cmpall/time_vs_triangles.dat' index 2 u ($1+0.0000):2:3:4 w yerrorlines lc 3 dt 1 pt 6 ps 0.8 notitle
set origin 0.333333,0.000000
set size 0.333333,0.895570
set title '256x128: trace'
set ylabel ''
set xlabel ''
set bmargin at screen 0.509494
set ytics ('20' 20, '50' 50, '100' 100, '200' 200)
plot '/tmp/cmpall/time_vs_triangles.dat' index 3 u ($1+0.0000):2:3:4 w yerrorlines lc 1 dt 1 pt 7 ps 0.8 notitle, '/tmp/cmpall/time_vs_triangles.dat' index 4 u ($1+0.0000):2:3:4 w yerrorlines lc 2 dt 1 pt 5 ps 0.8 notitle, '/tmp/cmpall/time_vs_triangles.dat' index 5 u ($1+0.0000):2:3:4 w yerrorlines lc 3 dt 1 pt 6 ps 0.8 notitle
set origin 0.666667,0.000000
set size 0.333333,0.895570
set title '256x128: frame'
set ylabel ''
set xlabel ''
set bmargin at screen 0.509494
set ytics ('50' 50, '100' 100, '200' 200)
plot '/tmp/cmpall/time_vs_triangles.dat' index 6 u ($1+0.0000):2:3:4 w yerrorlines lc 1 dt 1 pt 7 ps 0.8 notitle, '/tmp/cmpall/time_vs_triangles.dat' index 7 u ($1+0.0000):2:3:4 w yerrorlines lc 2 dt 1 pt 5 ps 0.8 notitle, '/tmp/cmpall/time_vs_triangles.dat' index 8 u ($1+0.0000):2:3:4 w yerrorlines lc 3 dt 1 pt 6 ps 0.8 notitle
unset multiplot
set output

# time_vs_triangles
reset
set terminal pngcairo noenhanced size 1020,632 font 'sans,9'
set for [i=1:8] linetype i lc rgb word('#0072b2 #d55e00 #009e73 #cc79a7 #e69f00 #56b4e9 #999999 #882255', i) lw 1.3
set output '/tmp/cmpall/time_vs_triangles.png'
set multiplot title 'Times vs the scenes'' triangles (log), per image size: the build, the trace passes, the whole frame (medians; bars: min-max of the repeats)'
unset border
unset tics
set xrange [0:1]
set yrange [0:1]
set key center center horizontal maxcols 3 samplen 2.5 reverse Left width 1 noautotitle
set origin 0,0.895570
set size 1,0.050633
set lmargin 0
set rmargin 0
set tmargin 0
set bmargin 0
plot NaN w lp lc 1 dt 1 pt 7 ps 0.8 t 'DIRT S1', NaN w lp lc 3 dt 1 pt 6 ps 0.8 t 'DIRT S2', NaN w lp lc 2 dt 1 pt 5 ps 0.8 t 'MMRT th default (0.2 %)'
set border
set tics
set key off
set grid
set autoscale
set autoscale fix
unset lmargin
unset rmargin
unset tmargin
unset bmargin
set offsets graph 0.08, graph 0.08, graph 0.08, graph 0.08
set format y '%g'
set logscale x
set logscale y
set xtics ('default (1478)' 1478, 'CornellBox.glb (36) / CornellBox-Original.obj (36)' 36, 'cornell_box.glb (4410)' 4410, 'AnimatedMorphCube.gltf (12)' 12, 'AnimatedTriangle.gltf (1)' 1, 'BoxAnimated.gltf (254)' 254, 'CesiumMan.glb (4672)' 4672, 'CesiumMilkTruck.gltf (3624)' 3624, 'FlightHelmet.gltf (94722)' 94722, 'Fox.glb (576)' 576, 'MorphStressTest.gltf (2412)' 2412, 'RiggedFigure.gltf (256)' 256, 'RiggedSimple.gltf (188)' 188, 'SimpleSkin.gltf (8)' 8) rotate by 90 right font ',8'
set origin 0.000000,0.000000
set size 0.333333,0.895570
set title '256x128: build'
set ylabel 'ms (log)'
set xlabel ''
set bmargin at screen 0.509494
set ytics ('1' 1, '10' 10, '100' 100)
plot '/tmp/cmpall/time_vs_triangles.dat' index 0 u ($1+0.0000):2:3:4 w yerrorlines lc 1 dt 1 pt 7 ps 0.8 notitle, '/tmp/cmpall/time_vs_triangles.dat' index 1 u ($1+0.0000):2:3:4 w yerrorlines lc 2 dt 1 pt 5 ps 0.8 notitle, '/tmp/cmpall/time_vs_triangles.dat' index 2 u ($1+0.0000):2:3:4 w yerrorlines lc 3 dt 1 pt 6 ps 0.8 notitle
set origin 0.333333,0.000000
set size 0.333333,0.895570
set title '256x128: trace'
set ylabel ''
set xlabel ''
set bmargin at screen 0.509494
set ytics ('20' 20, '50' 50, '100' 100, '200' 200)
plot '/tmp/cmpall/time_vs_triangles.dat' index 3 u ($1+0.0000):2:3:4 w yerrorlines lc 1 dt 1 pt 7 ps 0.8 notitle, '/tmp/cmpall/time_vs_triangles.dat' index 4 u ($1+0.0000):2:3:4 w yerrorlines lc 2 dt 1 pt 5 ps 0.8 notitle, '/tmp/cmpall/time_vs_triangles.dat' index 5 u ($1+0.0000):2:3:4 w yerrorlines lc 3 dt 1 pt 6 ps 0.8 notitle
set origin 0.666667,0.000000
set size 0.333333,0.895570
set title '256x128: frame'
set ylabel ''
set xlabel ''
set bmargin at screen 0.509494
set ytics ('50' 50, '100' 100, '200' 200)
plot '/tmp/cmpall/time_vs_triangles.dat' index 6 u ($1+0.0000):2:3:4 w yerrorlines lc 1 dt 1 pt 7 ps 0.8 notitle, '/tmp/cmpall/time_vs_triangles.dat' index 7 u ($1+0.0000):2:3:4 w yerrorlines lc 2 dt 1 pt 5 ps 0.8 notitle, '/tmp/cmpall/time_vs_triangles.dat' index 8 u ($1+0.0000):2:3:4 w yerrorlines lc 3 dt 1 pt 6 ps 0.8 notitle
unset multiplot
set output

# ratios_per_scene
reset
set terminal svg noenhanced size 1020,1366 font 'sans,9' background '#ffffff'
set for [i=1:8] linetype i lc rgb word('#0072b2 #d55e00 #009e73 #cc79a7 #e69f00 #56b4e9 #999999 #882255', i) lw 1.3
set output '/tmp/cmpall/ratios_per_scene.svg'
set multiplot title 'DIRT / MMRT per scene and image size (below 1: DIRT''s is smaller or faster; bars: the repeats'' extremes)'
unset border
unset tics
set xrange [0:1]
set yrange [0:1]
set key center center horizontal maxcols 3 samplen 2.5 reverse Left width 1 noautotitle
set origin 0,0.951684
set size 1,0.023426
set lmargin 0
set rmargin 0
set tmargin 0
set bmargin 0
plot NaN w p lc 1 dt 1 pt 5 ps 0.8 t 'DIRT S1 / MMRT th default (0.2 %)', NaN w p lc 2 dt 1 pt 9 ps 0.8 t 'DIRT S2 / MMRT th default (0.2 %)', NaN w l lc rgb 'black' lt 1 dt 2 t 'parity: DIRT = MMRT'
set border
set tics
set key off
set grid
set autoscale
set autoscale fix
unset lmargin
unset rmargin
unset tmargin
unset bmargin
set offsets graph 0, graph 0, graph 0.08, graph 0.08
set format y '%g'
unset logscale x
set logscale y
set xrange [0.5:5.5]
set xtics ('entries' 1, 'memory' 2, 'build' 3, 'trace' 4, 'frame' 5)
set origin 0.000000,0.761347
set size 0.333333,0.190337
set title 'default (1478 triangles), 256x128'
set ylabel 'DIRT / MMRT (log)'
set xlabel ''
set ytics ('0.1' 0.1, '0.2' 0.2, '0.5' 0.5, '1' 1)
plot '/tmp/cmpall/ratios_per_scene.dat' index 0 u ($1-0.1750):2:3:4 w yerrorbars lc 1 dt 1 pt 5 ps 0.8 notitle, '/tmp/cmpall/ratios_per_scene.dat' index 1 u 1:2 w l lc rgb 'black' dt 2 notitle, '/tmp/cmpall/ratios_per_scene.dat' index 2 u ($1+0.1750):2:3:4 w yerrorbars lc 2 dt 1 pt 9 ps 0.8 notitle
set origin 0.333333,0.761347
set size 0.333333,0.190337
set title 'CornellBox.glb (36 triangles), 256x128'
set ylabel ''
set xlabel ''
set ytics ('0.1' 0.1, '0.2' 0.2, '0.5' 0.5, '1' 1)
plot '/tmp/cmpall/ratios_per_scene.dat' index 3 u ($1-0.1750):2:3:4 w yerrorbars lc 1 dt 1 pt 5 ps 0.8 notitle, '/tmp/cmpall/ratios_per_scene.dat' index 4 u 1:2 w l lc rgb 'black' dt 2 notitle, '/tmp/cmpall/ratios_per_scene.dat' index 5 u ($1+0.1750):2:3:4 w yerrorbars lc 2 dt 1 pt 9 ps 0.8 notitle
set origin 0.666667,0.761347
set size 0.333333,0.190337
set title 'cornell_box.glb (4410 triangles), 256x128'
set ylabel ''
set xlabel ''
set ytics ('0.2' 0.2, '0.5' 0.5, '1' 1, '2' 2)
plot '/tmp/cmpall/ratios_per_scene.dat' index 6 u ($1-0.1750):2:3:4 w yerrorbars lc 1 dt 1 pt 5 ps 0.8 notitle, '/tmp/cmpall/ratios_per_scene.dat' index 7 u 1:2 w l lc rgb 'black' dt 2 notitle, '/tmp/cmpall/ratios_per_scene.dat' index 8 u ($1+0.1750):2:3:4 w yerrorbars lc 2 dt 1 pt 9 ps 0.8 notitle
set origin 0.000000,0.571010
set size 0.333333,0.190337
set title 'CornellBox-Original.obj (36 triangles), 256x128'
set ylabel 'DIRT / MMRT (log)'
set xlabel ''
set ytics ('0.1' 0.1, '0.2' 0.2, '0.5' 0.5, '1' 1)
plot '/tmp/cmpall/ratios_per_scene.dat' index 9 u ($1-0.1750):2:3:4 w yerrorbars lc 1 dt 1 pt 5 ps 0.8 notitle, '/tmp/cmpall/ratios_per_scene.dat' index 10 u 1:2 w l lc rgb 'black' dt 2 notitle, '/tmp/cmpall/ratios_per_scene.dat' index 11 u ($1+0.1750):2:3:4 w yerrorbars lc 2 dt 1 pt 9 ps 0.8 notitle
set origin 0.333333,0.571010
set size 0.333333,0.190337
set title 'AnimatedMorphCube.gltf (12 triangles), 256x128'
set ylabel ''
set xlabel ''
set ytics autofreq
plot '/tmp/cmpall/ratios_per_scene.dat' index 12 u ($1-0.1750):2:3:4 w yerrorbars lc 1 dt 1 pt 5 ps 0.8 notitle, '/tmp/cmpall/ratios_per_scene.dat' index 13 u 1:2 w l lc rgb 'black' dt 2 notitle, '/tmp/cmpall/ratios_per_scene.dat' index 14 u ($1+0.1750):2:3:4 w yerrorbars lc 2 dt 1 pt 9 ps 0.8 notitle
set origin 0.666667,0.571010
set size 0.333333,0.190337
set title 'AnimatedTriangle.gltf (1 triangles), 256x128'
set ylabel ''
set xlabel ''
set ytics autofreq
plot '/tmp/cmpall/ratios_per_scene.dat' index 15 u ($1-0.1750):2:3:4 w yerrorbars lc 1 dt 1 pt 5 ps 0.8 notitle, '/tmp/cmpall/ratios_per_scene.dat' index 16 u 1:2 w l lc rgb 'black' dt 2 notitle, '/tmp/cmpall/ratios_per_scene.dat' index 17 u ($1+0.1750):2:3:4 w yerrorbars lc 2 dt 1 pt 9 ps 0.8 notitle
set origin 0.000000,0.380673
set size 0.333333,0.190337
set title 'BoxAnimated.gltf (254 triangles), 256x128'
set ylabel 'DIRT / MMRT (log)'
set xlabel ''
set ytics ('0.2' 0.2, '0.5' 0.5, '1' 1, '2' 2)
plot '/tmp/cmpall/ratios_per_scene.dat' index 18 u ($1-0.1750):2:3:4 w yerrorbars lc 1 dt 1 pt 5 ps 0.8 notitle, '/tmp/cmpall/ratios_per_scene.dat' index 19 u 1:2 w l lc rgb 'black' dt 2 notitle, '/tmp/cmpall/ratios_per_scene.dat' index 20 u ($1+0.1750):2:3:4 w yerrorbars lc 2 dt 1 pt 9 ps 0.8 notitle
set origin 0.333333,0.380673
set size 0.333333,0.190337
set title 'CesiumMan.glb (4672 triangles), 256x128'
set ylabel ''
set xlabel ''
set ytics ('0.2' 0.2, '0.5' 0.5, '1' 1, '2' 2, '5' 5, '10' 10)
plot '/tmp/cmpall/ratios_per_scene.dat' index 21 u ($1-0.1750):2:3:4 w yerrorbars lc 1 dt 1 pt 5 ps 0.8 notitle, '/tmp/cmpall/ratios_per_scene.dat' index 22 u 1:2 w l lc rgb 'black' dt 2 notitle, '/tmp/cmpall/ratios_per_scene.dat' index 23 u ($1+0.1750):2:3:4 w yerrorbars lc 2 dt 1 pt 9 ps 0.8 notitle
set origin 0.666667,0.380673
set size 0.333333,0.190337
set title 'CesiumMilkTruck.gltf (3624 triangles), 256x128'
set ylabel ''
set xlabel ''
set ytics ('0.2' 0.2, '0.5' 0.5, '1' 1, '2' 2, '5' 5)
plot '/tmp/cmpall/ratios_per_scene.dat' index 24 u ($1-0.1750):2:3:4 w yerrorbars lc 1 dt 1 pt 5 ps 0.8 notitle, '/tmp/cmpall/ratios_per_scene.dat' index 25 u 1:2 w l lc rgb 'black' dt 2 notitle, '/tmp/cmpall/ratios_per_scene.dat' index 26 u ($1+0.1750):2:3:4 w yerrorbars lc 2 dt 1 pt 9 ps 0.8 notitle
set origin 0.000000,0.190337
set size 0.333333,0.190337
set title 'FlightHelmet.gltf (94722 triangles), 256x128'
set ylabel 'DIRT / MMRT (log)'
set xlabel ''
set ytics ('0.5' 0.5, '1' 1, '2' 2, '5' 5, '10' 10, '20' 20)
plot '/tmp/cmpall/ratios_per_scene.dat' index 27 u ($1-0.1750):2:3:4 w yerrorbars lc 1 dt 1 pt 5 ps 0.8 notitle, '/tmp/cmpall/ratios_per_scene.dat' index 28 u 1:2 w l lc rgb 'black' dt 2 notitle, '/tmp/cmpall/ratios_per_scene.dat' index 29 u ($1+0.1750):2:3:4 w yerrorbars lc 2 dt 1 pt 9 ps 0.8 notitle
set origin 0.333333,0.190337
set size 0.333333,0.190337
set title 'Fox.glb (576 triangles), 256x128'
set ylabel ''
set xlabel ''
set ytics ('0.2' 0.2, '0.5' 0.5, '1' 1, '2' 2, '5' 5)
plot '/tmp/cmpall/ratios_per_scene.dat' index 30 u ($1-0.1750):2:3:4 w yerrorbars lc 1 dt 1 pt 5 ps 0.8 notitle, '/tmp/cmpall/ratios_per_scene.dat' index 31 u 1:2 w l lc rgb 'black' dt 2 notitle, '/tmp/cmpall/ratios_per_scene.dat' index 32 u ($1+0.1750):2:3:4 w yerrorbars lc 2 dt 1 pt 9 ps 0.8 notitle
set origin 0.666667,0.190337
set size 0.333333,0.190337
set title 'MorphStressTest.gltf (2412 triangles), 256x128'
set ylabel ''
set xlabel ''
set ytics ('0.2' 0.2, '0.5' 0.5, '1' 1, '2' 2, '5' 5)
plot '/tmp/cmpall/ratios_per_scene.dat' index 33 u ($1-0.1750):2:3:4 w yerrorbars lc 1 dt 1 pt 5 ps 0.8 notitle, '/tmp/cmpall/ratios_per_scene.dat' index 34 u 1:2 w l lc rgb 'black' dt 2 notitle, '/tmp/cmpall/ratios_per_scene.dat' index 35 u ($1+0.1750):2:3:4 w yerrorbars lc 2 dt 1 pt 9 ps 0.8 notitle
set origin 0.000000,0.000000
set size 0.333333,0.190337
set title 'RiggedFigure.gltf (256 triangles), 256x128'
set ylabel 'DIRT / MMRT (log)'
set xlabel ''
set ytics ('0.2' 0.2, '0.5' 0.5, '1' 1, '2' 2)
plot '/tmp/cmpall/ratios_per_scene.dat' index 36 u ($1-0.1750):2:3:4 w yerrorbars lc 1 dt 1 pt 5 ps 0.8 notitle, '/tmp/cmpall/ratios_per_scene.dat' index 37 u 1:2 w l lc rgb 'black' dt 2 notitle, '/tmp/cmpall/ratios_per_scene.dat' index 38 u ($1+0.1750):2:3:4 w yerrorbars lc 2 dt 1 pt 9 ps 0.8 notitle
set origin 0.333333,0.000000
set size 0.333333,0.190337
set title 'RiggedSimple.gltf (188 triangles), 256x128'
set ylabel ''
set xlabel ''
set ytics ('0.2' 0.2, '0.5' 0.5, '1' 1, '2' 2, '5' 5)
plot '/tmp/cmpall/ratios_per_scene.dat' index 39 u ($1-0.1750):2:3:4 w yerrorbars lc 1 dt 1 pt 5 ps 0.8 notitle, '/tmp/cmpall/ratios_per_scene.dat' index 40 u 1:2 w l lc rgb 'black' dt 2 notitle, '/tmp/cmpall/ratios_per_scene.dat' index 41 u ($1+0.1750):2:3:4 w yerrorbars lc 2 dt 1 pt 9 ps 0.8 notitle
set origin 0.666667,0.000000
set size 0.333333,0.190337
set title 'SimpleSkin.gltf (8 triangles), 256x128'
set ylabel ''
set xlabel ''
set ytics autofreq
plot '/tmp/cmpall/ratios_per_scene.dat' index 42 u ($1-0.1750):2:3:4 w yerrorbars lc 1 dt 1 pt 5 ps 0.8 notitle, '/tmp/cmpall/ratios_per_scene.dat' index 43 u 1:2 w l lc rgb 'black' dt 2 notitle, '/tmp/cmpall/ratios_per_scene.dat' index 44 u ($1+0.1750):2:3:4 w yerrorbars lc 2 dt 1 pt 9 ps 0.8 notitle
unset multiplot
set output

# ratios_per_scene
reset
set terminal pngcairo noenhanced size 1020,1366 font 'sans,9'
set for [i=1:8] linetype i lc rgb word('#0072b2 #d55e00 #009e73 #cc79a7 #e69f00 #56b4e9 #999999 #882255', i) lw 1.3
set output '/tmp/cmpall/ratios_per_scene.png'
set multiplot title 'DIRT / MMRT per scene and image size (below 1: DIRT''s is smaller or faster; bars: the repeats'' extremes)'
unset border
unset tics
set xrange [0:1]
set yrange [0:1]
set key center center horizontal maxcols 3 samplen 2.5 reverse Left width 1 noautotitle
set origin 0,0.951684
set size 1,0.023426
set lmargin 0
set rmargin 0
set tmargin 0
set bmargin 0
plot NaN w p lc 1 dt 1 pt 5 ps 0.8 t 'DIRT S1 / MMRT th default (0.2 %)', NaN w p lc 2 dt 1 pt 9 ps 0.8 t 'DIRT S2 / MMRT th default (0.2 %)', NaN w l lc rgb 'black' lt 1 dt 2 t 'parity: DIRT = MMRT'
set border
set tics
set key off
set grid
set autoscale
set autoscale fix
unset lmargin
unset rmargin
unset tmargin
unset bmargin
set offsets graph 0, graph 0, graph 0.08, graph 0.08
set format y '%g'
unset logscale x
set logscale y
set xrange [0.5:5.5]
set xtics ('entries' 1, 'memory' 2, 'build' 3, 'trace' 4, 'frame' 5)
set origin 0.000000,0.761347
set size 0.333333,0.190337
set title 'default (1478 triangles), 256x128'
set ylabel 'DIRT / MMRT (log)'
set xlabel ''
set ytics ('0.1' 0.1, '0.2' 0.2, '0.5' 0.5, '1' 1)
plot '/tmp/cmpall/ratios_per_scene.dat' index 0 u ($1-0.1750):2:3:4 w yerrorbars lc 1 dt 1 pt 5 ps 0.8 notitle, '/tmp/cmpall/ratios_per_scene.dat' index 1 u 1:2 w l lc rgb 'black' dt 2 notitle, '/tmp/cmpall/ratios_per_scene.dat' index 2 u ($1+0.1750):2:3:4 w yerrorbars lc 2 dt 1 pt 9 ps 0.8 notitle
set origin 0.333333,0.761347
set size 0.333333,0.190337
set title 'CornellBox.glb (36 triangles), 256x128'
set ylabel ''
set xlabel ''
set ytics ('0.1' 0.1, '0.2' 0.2, '0.5' 0.5, '1' 1)
plot '/tmp/cmpall/ratios_per_scene.dat' index 3 u ($1-0.1750):2:3:4 w yerrorbars lc 1 dt 1 pt 5 ps 0.8 notitle, '/tmp/cmpall/ratios_per_scene.dat' index 4 u 1:2 w l lc rgb 'black' dt 2 notitle, '/tmp/cmpall/ratios_per_scene.dat' index 5 u ($1+0.1750):2:3:4 w yerrorbars lc 2 dt 1 pt 9 ps 0.8 notitle
set origin 0.666667,0.761347
set size 0.333333,0.190337
set title 'cornell_box.glb (4410 triangles), 256x128'
set ylabel ''
set xlabel ''
set ytics ('0.2' 0.2, '0.5' 0.5, '1' 1, '2' 2)
plot '/tmp/cmpall/ratios_per_scene.dat' index 6 u ($1-0.1750):2:3:4 w yerrorbars lc 1 dt 1 pt 5 ps 0.8 notitle, '/tmp/cmpall/ratios_per_scene.dat' index 7 u 1:2 w l lc rgb 'black' dt 2 notitle, '/tmp/cmpall/ratios_per_scene.dat' index 8 u ($1+0.1750):2:3:4 w yerrorbars lc 2 dt 1 pt 9 ps 0.8 notitle
set origin 0.000000,0.571010
set size 0.333333,0.190337
set title 'CornellBox-Original.obj (36 triangles), 256x128'
set ylabel 'DIRT / MMRT (log)'
set xlabel ''
set ytics ('0.1' 0.1, '0.2' 0.2, '0.5' 0.5, '1' 1)
plot '/tmp/cmpall/ratios_per_scene.dat' index 9 u ($1-0.1750):2:3:4 w yerrorbars lc 1 dt 1 pt 5 ps 0.8 notitle, '/tmp/cmpall/ratios_per_scene.dat' index 10 u 1:2 w l lc rgb 'black' dt 2 notitle, '/tmp/cmpall/ratios_per_scene.dat' index 11 u ($1+0.1750):2:3:4 w yerrorbars lc 2 dt 1 pt 9 ps 0.8 notitle
set origin 0.333333,0.571010
set size 0.333333,0.190337
set title 'AnimatedMorphCube.gltf (12 triangles), 256x128'
set ylabel ''
set xlabel ''
set ytics autofreq
plot '/tmp/cmpall/ratios_per_scene.dat' index 12 u ($1-0.1750):2:3:4 w yerrorbars lc 1 dt 1 pt 5 ps 0.8 notitle, '/tmp/cmpall/ratios_per_scene.dat' index 13 u 1:2 w l lc rgb 'black' dt 2 notitle, '/tmp/cmpall/ratios_per_scene.dat' index 14 u ($1+0.1750):2:3:4 w yerrorbars lc 2 dt 1 pt 9 ps 0.8 notitle
set origin 0.666667,0.571010
set size 0.333333,0.190337
set title 'AnimatedTriangle.gltf (1 triangles), 256x128'
set ylabel ''
set xlabel ''
set ytics autofreq
plot '/tmp/cmpall/ratios_per_scene.dat' index 15 u ($1-0.1750):2:3:4 w yerrorbars lc 1 dt 1 pt 5 ps 0.8 notitle, '/tmp/cmpall/ratios_per_scene.dat' index 16 u 1:2 w l lc rgb 'black' dt 2 notitle, '/tmp/cmpall/ratios_per_scene.dat' index 17 u ($1+0.1750):2:3:4 w yerrorbars lc 2 dt 1 pt 9 ps 0.8 notitle
set origin 0.000000,0.380673
set size 0.333333,0.190337
set title 'BoxAnimated.gltf (254 triangles), 256x128'
set ylabel 'DIRT / MMRT (log)'
set xlabel ''
set ytics ('0.2' 0.2, '0.5' 0.5, '1' 1, '2' 2)
plot '/tmp/cmpall/ratios_per_scene.dat' index 18 u ($1-0.1750):2:3:4 w yerrorbars lc 1 dt 1 pt 5 ps 0.8 notitle, '/tmp/cmpall/ratios_per_scene.dat' index 19 u 1:2 w l lc rgb 'black' dt 2 notitle, '/tmp/cmpall/ratios_per_scene.dat' index 20 u ($1+0.1750):2:3:4 w yerrorbars lc 2 dt 1 pt 9 ps 0.8 notitle
set origin 0.333333,0.380673
set size 0.333333,0.190337
set title 'CesiumMan.glb (4672 triangles), 256x128'
set ylabel ''
set xlabel ''
set ytics ('0.2' 0.2, '0.5' 0.5, '1' 1, '2' 2, '5' 5, '10' 10)
plot '/tmp/cmpall/ratios_per_scene.dat' index 21 u ($1-0.1750):2:3:4 w yerrorbars lc 1 dt 1 pt 5 ps 0.8 notitle, '/tmp/cmpall/ratios_per_scene.dat' index 22 u 1:2 w l lc rgb 'black' dt 2 notitle, '/tmp/cmpall/ratios_per_scene.dat' index 23 u ($1+0.1750):2:3:4 w yerrorbars lc 2 dt 1 pt 9 ps 0.8 notitle
set origin 0.666667,0.380673
set size 0.333333,0.190337
set title 'CesiumMilkTruck.gltf (3624 triangles), 256x128'
set ylabel ''
set xlabel ''
set ytics ('0.2' 0.2, '0.5' 0.5, '1' 1, '2' 2, '5' 5)
plot '/tmp/cmpall/ratios_per_scene.dat' index 24 u ($1-0.1750):2:3:4 w yerrorbars lc 1 dt 1 pt 5 ps 0.8 notitle, '/tmp/cmpall/ratios_per_scene.dat' index 25 u 1:2 w l lc rgb 'black' dt 2 notitle, '/tmp/cmpall/ratios_per_scene.dat' index 26 u ($1+0.1750):2:3:4 w yerrorbars lc 2 dt 1 pt 9 ps 0.8 notitle
set origin 0.000000,0.190337
set size 0.333333,0.190337
set title 'FlightHelmet.gltf (94722 triangles), 256x128'
set ylabel 'DIRT / MMRT (log)'
set xlabel ''
set ytics ('0.5' 0.5, '1' 1, '2' 2, '5' 5, '10' 10, '20' 20)
plot '/tmp/cmpall/ratios_per_scene.dat' index 27 u ($1-0.1750):2:3:4 w yerrorbars lc 1 dt 1 pt 5 ps 0.8 notitle, '/tmp/cmpall/ratios_per_scene.dat' index 28 u 1:2 w l lc rgb 'black' dt 2 notitle, '/tmp/cmpall/ratios_per_scene.dat' index 29 u ($1+0.1750):2:3:4 w yerrorbars lc 2 dt 1 pt 9 ps 0.8 notitle
set origin 0.333333,0.190337
set size 0.333333,0.190337
set title 'Fox.glb (576 triangles), 256x128'
set ylabel ''
set xlabel ''
set ytics ('0.2' 0.2, '0.5' 0.5, '1' 1, '2' 2, '5' 5)
plot '/tmp/cmpall/ratios_per_scene.dat' index 30 u ($1-0.1750):2:3:4 w yerrorbars lc 1 dt 1 pt 5 ps 0.8 notitle, '/tmp/cmpall/ratios_per_scene.dat' index 31 u 1:2 w l lc rgb 'black' dt 2 notitle, '/tmp/cmpall/ratios_per_scene.dat' index 32 u ($1+0.1750):2:3:4 w yerrorbars lc 2 dt 1 pt 9 ps 0.8 notitle
set origin 0.666667,0.190337
set size 0.333333,0.190337
set title 'MorphStressTest.gltf (2412 triangles), 256x128'
set ylabel ''
set xlabel ''
set ytics ('0.2' 0.2, '0.5' 0.5, '1' 1, '2' 2, '5' 5)
plot '/tmp/cmpall/ratios_per_scene.dat' index 33 u ($1-0.1750):2:3:4 w yerrorbars lc 1 dt 1 pt 5 ps 0.8 notitle, '/tmp/cmpall/ratios_per_scene.dat' index 34 u 1:2 w l lc rgb 'black' dt 2 notitle, '/tmp/cmpall/ratios_per_scene.dat' index 35 u ($1+0.1750):2:3:4 w yerrorbars lc 2 dt 1 pt 9 ps 0.8 notitle
set origin 0.000000,0.000000
set size 0.333333,0.190337
set title 'RiggedFigure.gltf (256 triangles), 256x128'
set ylabel 'DIRT / MMRT (log)'
set xlabel ''
set ytics ('0.2' 0.2, '0.5' 0.5, '1' 1, '2' 2)
plot '/tmp/cmpall/ratios_per_scene.dat' index 36 u ($1-0.1750):2:3:4 w yerrorbars lc 1 dt 1 pt 5 ps 0.8 notitle, '/tmp/cmpall/ratios_per_scene.dat' index 37 u 1:2 w l lc rgb 'black' dt 2 notitle, '/tmp/cmpall/ratios_per_scene.dat' index 38 u ($1+0.1750):2:3:4 w yerrorbars lc 2 dt 1 pt 9 ps 0.8 notitle
set origin 0.333333,0.000000
set size 0.333333,0.190337
set title 'RiggedSimple.gltf (188 triangles), 256x128'
set ylabel ''
set xlabel ''
set ytics ('0.2' 0.2, '0.5' 0.5, '1' 1, '2' 2, '5' 5)
plot '/tmp/cmpall/ratios_per_scene.dat' index 39 u ($1-0.1750):2:3:4 w yerrorbars lc 1 dt 1 pt 5 ps 0.8 notitle, '/tmp/cmpall/ratios_per_scene.dat' index 40 u 1:2 w l lc rgb 'black' dt 2 notitle, '/tmp/cmpall/ratios_per_scene.dat' index 41 u ($1+0.1750):2:3:4 w yerrorbars lc 2 dt 1 pt 9 ps 0.8 notitle
set origin 0.666667,0.000000
set size 0.333333,0.190337
set title 'SimpleSkin.gltf (8 triangles), 256x128'
set ylabel ''
set xlabel ''
set ytics autofreq
plot '/tmp/cmpall/ratios_per_scene.dat' index 42 u ($1-0.1750):2:3:4 w yerrorbars lc 1 dt 1 pt 5 ps 0.8 notitle, '/tmp/cmpall/ratios_per_scene.dat' index 43 u 1:2 w l lc rgb 'black' dt 2 notitle, '/tmp/cmpall/ratios_per_scene.dat' index 44 u ($1+0.1750):2:3:4 w yerrorbars lc 2 dt 1 pt 9 ps 0.8 notitle
unset multiplot
set output
