D = 'perf/results/compare-llvmpipe-all/plot.dat'
NB = 15
RT = 'primary visibility specular glossy diffuse'
SC = 'default CornellBox.glb cornell-box.glb CornellBox-Original.obj AnimatedMorphCube.gltf AnimatedTriangle.gltf BoxAnimated.gltf CesiumMan.glb CesiumMilkTruck.gltf FlightHelmet.gltf Fox.glb MorphStressTest.gltf RiggedFigure.gltf RiggedSimple.gltf SimpleSkin.gltf'
set key outside right
set grid
set datafile missing 'NaN'
set terminal svg noenhanced size 900,500
set output 'perf/results/compare-llvmpipe-all/memory_vs_resolution.svg'
set title 'memory vs resolution'
set xlabel 'pixels'
set ylabel 'structure MB'
set logscale x
if (NB > 4) { set key below horizontal font ',7' }
plot for [i=0:NB-1] D u 2:4 index i w lp t word(SC, i+1).' MMRT', for [i=0:NB-1] D u 2:5 index i w lp dt 2 t word(SC, i+1).' DIRT'
set key outside right vertical font ''
set output
set terminal pngcairo noenhanced size 900,500
set output 'perf/results/compare-llvmpipe-all/memory_vs_resolution.png'
set title 'memory vs resolution'
set xlabel 'pixels'
set ylabel 'structure MB'
set logscale x
if (NB > 4) { set key below horizontal font ',7' }
plot for [i=0:NB-1] D u 2:4 index i w lp t word(SC, i+1).' MMRT', for [i=0:NB-1] D u 2:5 index i w lp dt 2 t word(SC, i+1).' DIRT'
set key outside right vertical font ''
set output
set terminal svg noenhanced size 900,500
set output 'perf/results/compare-llvmpipe-all/time_vs_resolution.svg'
set title 'time vs resolution'
set xlabel 'pixels'
set ylabel 'median ms'
set logscale x
if (NB > 2) { set key below horizontal font ',7' }
plot for [i=0:NB-1] D u 2:6 index i w lp t word(SC, i+1).' MMRT build', for [i=0:NB-1] D u 2:7 index i w lp t word(SC, i+1).' DIRT build', for [i=0:NB-1] D u 2:8 index i w lp dt 2 t word(SC, i+1).' MMRT trace', for [i=0:NB-1] D u 2:9 index i w lp dt 2 t word(SC, i+1).' DIRT trace'
set key outside right vertical font ''
set output
set terminal pngcairo noenhanced size 900,500
set output 'perf/results/compare-llvmpipe-all/time_vs_resolution.png'
set title 'time vs resolution'
set xlabel 'pixels'
set ylabel 'median ms'
set logscale x
if (NB > 2) { set key below horizontal font ',7' }
plot for [i=0:NB-1] D u 2:6 index i w lp t word(SC, i+1).' MMRT build', for [i=0:NB-1] D u 2:7 index i w lp t word(SC, i+1).' DIRT build', for [i=0:NB-1] D u 2:8 index i w lp dt 2 t word(SC, i+1).' MMRT trace', for [i=0:NB-1] D u 2:9 index i w lp dt 2 t word(SC, i+1).' DIRT trace'
set key outside right vertical font ''
set output
set terminal svg noenhanced size 900,500
set output 'perf/results/compare-llvmpipe-all/memory_vs_triangles.svg'
set title 'memory vs triangles'
set xlabel 'triangles'
set ylabel 'structure MB'
set logscale x
plot D u 3:4 w p pt 7 t 'MMRT', D u 3:5 w p pt 5 t 'DIRT'
set output
set terminal pngcairo noenhanced size 900,500
set output 'perf/results/compare-llvmpipe-all/memory_vs_triangles.png'
set title 'memory vs triangles'
set xlabel 'triangles'
set ylabel 'structure MB'
set logscale x
plot D u 3:4 w p pt 7 t 'MMRT', D u 3:5 w p pt 5 t 'DIRT'
set output
set terminal svg noenhanced size 900,500
set output 'perf/results/compare-llvmpipe-all/time_vs_triangles.svg'
set title 'time vs triangles'
set xlabel 'triangles'
set ylabel 'median ms'
set logscale x
plot D u 3:6 w p pt 7 t 'MMRT build', D u 3:7 w p pt 5 t 'DIRT build', D u 3:8 w p pt 6 t 'MMRT trace', D u 3:9 w p pt 4 t 'DIRT trace'
set output
set terminal pngcairo noenhanced size 900,500
set output 'perf/results/compare-llvmpipe-all/time_vs_triangles.png'
set title 'time vs triangles'
set xlabel 'triangles'
set ylabel 'median ms'
set logscale x
plot D u 3:6 w p pt 7 t 'MMRT build', D u 3:7 w p pt 5 t 'DIRT build', D u 3:8 w p pt 6 t 'MMRT trace', D u 3:9 w p pt 4 t 'DIRT trace'
set output
set terminal svg noenhanced size 900,760
set output 'perf/results/compare-llvmpipe-all/ratios_per_scene.svg'
set title 'ratios per scene'
set xlabel 'configuration'
set ylabel 'DIRT / MMRT'
unset logscale x
set xtics rotate by -45 font ',8'
plot D u 27:10:xtic(28) w lp t 'memory', D u 27:11 w lp t 'build', D u 27:12 w lp t 'trace', D u 27:26 w lp t 'frame'
set xtics norotate font ''
set output
set terminal pngcairo noenhanced size 900,760
set output 'perf/results/compare-llvmpipe-all/ratios_per_scene.png'
set title 'ratios per scene'
set xlabel 'configuration'
set ylabel 'DIRT / MMRT'
unset logscale x
set xtics rotate by -45 font ',8'
plot D u 27:10:xtic(28) w lp t 'memory', D u 27:11 w lp t 'build', D u 27:12 w lp t 'trace', D u 27:26 w lp t 'frame'
set xtics norotate font ''
set output
set terminal svg noenhanced size 900,500
set output 'perf/results/compare-llvmpipe-all/agreement_vs_thickness.svg'
set title 'agreement vs thickness'
set xlabel 'MMRT thickness / scene diagonal'
set ylabel 'agreement with Embree %'
set logscale x
plot for [k=0:4] D u 13:(column(14+2*k)) w lp t word(RT, k+1)
set output
set terminal pngcairo noenhanced size 900,500
set output 'perf/results/compare-llvmpipe-all/agreement_vs_thickness.png'
set title 'agreement vs thickness'
set xlabel 'MMRT thickness / scene diagonal'
set ylabel 'agreement with Embree %'
set logscale x
plot for [k=0:4] D u 13:(column(14+2*k)) w lp t word(RT, k+1)
set output
