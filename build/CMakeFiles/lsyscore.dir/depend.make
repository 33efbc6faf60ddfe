# Empty dependencies file for lsyscore.
# This may be replaced when dependencies are built.
