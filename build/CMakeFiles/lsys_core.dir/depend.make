# Empty dependencies file for lsys_core.
# This may be replaced when dependencies are built.
