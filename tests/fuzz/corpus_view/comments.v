/* a comment
 over lines */ angle factor: 4 // and one to the end
Angle   Factor : 6
front distance: 1
scale factor: 2
