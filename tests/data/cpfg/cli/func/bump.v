angle increment: 30
function: bump.func
