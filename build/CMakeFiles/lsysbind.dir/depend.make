# Empty dependencies file for lsysbind.
# This may be replaced when dependencies are built.
