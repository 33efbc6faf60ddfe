file(REMOVE_RECURSE
  "liblsyscore.a"
)
