function: br.func
function: exact.func
