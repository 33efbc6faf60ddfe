# Empty dependencies file for lsys.
# This may be replaced when dependencies are built.
