executable: honda81 collide.spec
communication type: pipes
turtle position: %g %g %g
