executable: MonteCarlo montecarlo.s
communication type: pipes
turtle position: %g %g %g
turtle heading: %g %g %g
turtle left: %g %g %g
turtle up: %g %g %g
following module: yes
interpreted modules: Z
