texture: F: a.png H: l L: m E: b S: R: 2
surface: A a.s 1 4 4 1
surface: B b.s 2 1
