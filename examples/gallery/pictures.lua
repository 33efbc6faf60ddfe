-- The gallery's pictures: what each shows and how it is drawn, for examples/gallery/make.lua,
-- which draws them and writes the page, and tests/gallery_spec.lua, which measures them
-- (no organ nearly black).
local render = require "lsys.render"

local M = {}

-- { file, model name (files returning a table of models), title, caption, view overrides,
--   png = name (default: from file and model), width =, height = (pixels at SIZE 480;
--   default SIZE), render = { options of lsys.render, e.g. wireframe = true } }
M.PICTURES = {
  { "default.lua", nil, "The default tree",
    "What `lsys render` draws without a model: a ternary tree with random angles, bent down "
    .. "by gravity, with whorls of rhombic leaves on the young shoots; cylinders in perspective." },
  { "abop/fig1_24a.lua", nil, "ABOP 1.24a",
    "Edge rewriting F → F[+F]F[-F]F, n = 5, δ = 25.7°: a tall axis with short side shoots." },
  { "abop/fig1_24b.lua", nil, "ABOP 1.24b",
    "Edge rewriting with a third, straight branch in each successor, n = 5, δ = 20°." },
  { "abop/fig1_24c.lua", nil, "ABOP 1.24c",
    "Edge rewriting with two curved three-segment branches per node, n = 4, δ = 22.5°; "
    .. "the bush leans to the right." },
  { "abop/fig1_24d.lua", nil, "ABOP 1.24d",
    "Node rewriting with an apex X, n = 7, δ = 20°: internodes double each step, so the "
    .. "lower stem is long and bare." },
  { "abop/fig1_24e.lua", nil, "ABOP 1.24e",
    "Node rewriting with opposite branches, n = 7, δ = 25.7°: a symmetric, pinnate plant." },
  { "abop/fig1_24f.lua", nil, "ABOP 1.24f",
    "Node rewriting with a nested bracket, n = 5, δ = 22.5°: a sparse, weed-like plant." },
  { "abop/fig1_25.lua", nil, "ABOP 1.25",
    "A three-dimensional bush, n = 7: branches thin and turn from brown to green with their "
    .. "order, and every internode carries a leaf polygon." },
  { "abop/fig1_27.lua", nil, "ABOP 1.27",
    "Stochastic branching: each F takes one of three successors at random (seed 1); a new "
    .. "seed gives another plant of the same kind." },
  { "abop/fig2_06.lua", "a", "ABOP 2.6a",
    "Monopodial tree after Honda: a straight trunk with lateral branches placed 137.5° "
    .. "apart; branches contract by 0.6." },
  { "abop/fig2_06.lua", "b", "ABOP 2.6b",
    "The same architecture with branch contraction 0.9: long, wide-spreading branches." },
  { "abop/fig2_06.lua", "c", "ABOP 2.6c", "Branch contraction 0.8: in between a and b." },
  { "abop/fig2_06.lua", "d", "ABOP 2.6d",
    "Branching angles of 30° and −30° and contraction 0.7: a narrow, upright crown." },
  { "abop/fig2_07.lua", "a", "ABOP 2.7a",
    "Sympodial tree after Aono and Kunii: each apex forks into two unequal branches "
    .. "(5° and 65°)." },
  { "abop/fig2_07.lua", "b", "ABOP 2.7b", "Branching angles 10° and 60°." },
  { "abop/fig2_07.lua", "c", "ABOP 2.7c", "Branching angles 20° and 50°, contraction 0.8." },
  { "abop/fig2_07.lua", "d", "ABOP 2.7d",
    "Equal angles of 35°: a symmetric fork at every node and a flat, spreading crown." },
  { "abop/fig2_08.lua", "a", "ABOP 2.8a",
    "Ternary branching bent down by a tropism toward −y (elasticity 0.22), n = 6." },
  { "abop/fig2_08.lua", "b", "ABOP 2.8b",
    "Divergence 137.5° between all three shoots and a weaker bend, n = 8: a dense, "
    .. "dome-shaped crown." },
  { "abop/fig2_08.lua", "c", "ABOP 2.8c",
    "Internodes that grow by 1.79 per step, n = 8: a very tall, thin trunk under a small "
    .. "crown of fine twigs." },
  { "abop/fig2_08.lua", "d", "ABOP 2.8d",
    "A tropism vector pointing up and to the left (elasticity 0.4): the whole tree leans "
    .. "as if shaped by wind." },
  { "abop/fig1_06.lua", nil, "ABOP 1.6",
    "Quadratic Koch island, n = 3: every edge of a square replaced three times by an "
    .. "eight-edge generator." },
  { "abop/fig1_10a.lua", nil, "ABOP 1.10a",
    "Dragon curve by edge rewriting with left and right edges, n = 10." },
  { "abop/fig1_11a.lua", nil, "ABOP 1.11a",
    "Hexagonal Gosper curve (flowsnake) by edge rewriting, n = 4, δ = 60°." },
  -- the cpfg guide: generalized cylinders, surfaces, textures; examples/cpfg
  { "cpfg/fig05.lua", "a", "Fig. 5a",
    "`@Gs f -(45) f @Ge(6)`: the turtle path (grey), the two control points and the Hermite "
    .. "curve between them; the curve leaves along the first heading and arrives along the "
    .. "second.", width = 320, height = 320 },
  { "cpfg/fig05.lua", "b", "Fig. 5b",
    "The same curve swept by a disc of radius 0.2 in 6 mesh strips.", width = 320, height = 320 },
  { "cpfg/fig05.lua", "b", "Fig. 5c",
    "The same generalized cylinder as a wireframe: 6 strips of 8 quadrilaterals, flat caps.",
    png = "cpfg/fig05_c.png", width = 320, height = 320, render = { wireframe = true } },
  { "cpfg/fig06.lua", nil, "Fig. 6",
    "The cylinder of fig. 5 with 1 to 5 mesh strips (wireframe): one strip is a straight "
    .. "sheared tube, the bend appears as strips are added.", width = 640, height = 240,
    render = { wireframe = true } },
  { "cpfg/fig07.lua", "a", "Fig. 7a",
    "The snake kolam, n = 2, drawn with lines.", width = 320, height = 320 },
  { "cpfg/fig07.lua", "b", "Fig. 7b",
    "The same curve as one closed generalized cylinder with a control point in the middle "
    .. "of every segment (F → f @Gc(4) f): the corners become arcs.", width = 320, height = 320 },
  { "cpfg/fig09.lua", "a", "Fig. 9a",
    "The longitudinal section R(t) of `@Gr(30,4.5,0,3.5)`: from radius 0.2 to 0.1 over a "
    .. "unit length, with tangents of 30° and 0°.", width = 320, height = 320 },
  { "cpfg/fig09.lua", "bcd", "Fig. 9b–d",
    "That section on a cylinder of length 1 (b) and 1.5 (c, d); d keeps the tangent angles "
    .. "on the longer segment (@Gr(1)).", width = 320, height = 320 },
  { "cpfg/fig10.lua", "a", "Fig. 10a",
    "The same section on a curved cylinder `@Gs -(45) f -(45) @Ge(20)`: the bulge follows "
    .. "the bend.", width = 320, height = 320 },
  { "cpfg/fig08.lua", nil, "Fig. 8",
    "Tangent coefficients of the axis, left to right: 1.2,1.2 (default); 2,2; 0.5,0.5; 4,1; "
    .. "3,−2. Grey: the tangent vectors at 1/4 of their length.", width = 800, height = 240 },
  { "cpfg/fig10.lua", "b", "Fig. 10b",
    "Cross-sections swept along a bent axis, each perpendicular to it (wireframe).",
    width = 320, height = 320, render = { wireframe = true } },
  { "cpfg/fig10.lua", "c", "Fig. 10c",
    "A radius larger than the radius of curvature: the cross-sections cross on the inside "
    .. "of the bend (wireframe).", width = 320, height = 320, render = { wireframe = true } },
  { "cpfg/fig11.lua", "a", "Fig. 11a",
    "A shell: 117 segments of a helico-spiral (R 1.03, 20°, 2.1°) as one tapering generalized "
    .. "cylinder with linear radius interpolation.", width = 320, height = 320 },
  { "cpfg/fig11.lua", "b", "Fig. 11b",
    "The precious wentletrap (reconstructed): the radius tangents of @Gr shape a rib at every "
    .. "other segment; a tall, open spire.", width = 320, height = 320 },
  { "cpfg/fig12.lua", "a", "Fig. 12a",
    "A closed contour file: 12 control points (the first bigger), the closed B-spline and the "
    .. "unit circle.", width = 320, height = 320 },
  { "cpfg/fig12.lua", "b", "Fig. 12b",
    "The contour at both ends of a straight generalized cylinder, 32 sides.",
    width = 320, height = 320 },
  { "cpfg/fig12.lua", "c", "Fig. 12c",
    "A circle at the base and the contour at the top: the cross-section blends from one into "
    .. "the other.", width = 320, height = 320 },
  { "cpfg/fig13.lua", "a", "Fig. 13a",
    "The contour of fig. 12 in 3D: the first control point is lifted by 1 along the axis.",
    width = 320, height = 320 },
  { "cpfg/fig13.lua", "b", "Fig. 13b",
    "The 3D contour at both ends: a tongue rises from the rim along the axis.",
    width = 320, height = 320 },
  { "cpfg/fig13.lua", "c", "Fig. 13c",
    "A circle at the base and the 3D contour at the top.", width = 320, height = 320 },
  { "cpfg/fig14.lua", "b", "Fig. 14b",
    "A stem segment with an 8-ribbed star contour and a pointed tip (radius tangent −45°).",
    width = 320, height = 320 },
  { "cpfg/fig14.lua", "c", "Fig. 14c",
    "The cactus Lemaireocereus chende: the guide's stochastic L-system (seed 2, 16 steps); "
    .. "the branches bend up under a tropism, apices that point down are cut.",
    width = 320, height = 320 },
  { "cpfg/fig15.lua", "a", "Fig. 15b",
    "An aloe leaf: two control points, a keeled leaf contour and a bulging longitudinal "
    .. "section (@Gr).", width = 320, height = 320 },
  { "cpfg/fig15.lua", "c", "Fig. 15c",
    "Aloe variegata (reconstructed): a rosette of banded (textured) leaves in three ranks, a "
    .. "tapering stalk and a raceme of pendulous six-lobed flowers.", width = 320, height = 320 },
  { "cpfg/fig16.lua", "a", "Fig. 16a",
    "An open contour: 15 control points, the first and last repeated three times.",
    width = 320, height = 320 },
  { "cpfg/fig16.lua", "b", "Fig. 16b",
    "A long leaf blade: one curved segment of length 10 with the open contour and a bulging "
    .. "section, seen face on.", width = 320, height = 320 },
  { "cpfg/fig16.lua", "c", "Fig. 16c",
    "The same blade from the side: the open, wavy cross-section.", width = 320, height = 320 },
  { "cpfg/fig17.lua", "a", "Fig. 17a",
    "An open, nearly straight contour swept along a helico-spiral (R 1.04, Ang3 78°): a "
    .. "conical shell.", width = 320, height = 320 },
  { "cpfg/fig17.lua", "b", "Fig. 17b",
    "A triangular open contour (R 1.02, Ang3 80°): whorls with a sharp keel.",
    width = 320, height = 320 },
  { "cpfg/fig17.lua", "c", "Fig. 17c",
    "Two contours alternating between odd and even segments: a row of knobs on each whorl.",
    width = 320, height = 320 },
  { "cpfg/fig18.lua", nil, "Fig. 18",
    "The pelican's foot shell: the contours of fig. 17c and, on the last, doubled segment, a "
    .. "third contour that flares into a lip with fingers.", width = 320, height = 320 },
  { "cpfg/fig19.lua", "a", "Fig. 19a",
    "`@Gs f -(30) f /(180) @Ge(10)` with a star contour and twist minimisation off: the roll "
    .. "twists the segment by 180°.", width = 320, height = 320 },
  { "cpfg/fig19.lua", "b", "Fig. 19b",
    "The same string with the twist minimised (the default): the roll has no effect.",
    width = 320, height = 320 },
  { "cpfg/fig19.lua", "c", "Fig. 19c",
    "A twisted column: a roll of 12° before each of 32 control points, twist minimisation "
    .. "off.", width = 320, height = 320 },
  { "cpfg/fig21.lua", "a", "Fig. 21a",
    "A branch fork `B F [ +(40) ! F E ] [ -(25) ! F E ]` drawn with straight cylinders.",
    width = 320, height = 320 },
  { "cpfg/fig21.lua", "b", "Fig. 21b",
    "The parametric curves of the homomorphism F → f(0.5) @Gc(4) f(0.5) and their control "
    .. "points; both branches leave from the same point.", width = 320, height = 320 },
  { "cpfg/fig21.lua", "c", "Fig. 21c",
    "The generalized cylinders (wireframe): the two daughter branches overlap at the fork.",
    width = 320, height = 320, render = { wireframe = true } },
  { "cpfg/fig21.lua", "c", "Fig. 21d",
    "The same cylinders shaded: a smooth fork.", png = "cpfg/fig21_d.png",
    width = 320, height = 320 },
  { "cpfg/fig22.lua", nil, "Fig. 22",
    "An apple blossom, 2 steps, δ = 18°: five calyx leaves and petals (predefined Bézier "
    .. "surfaces ~C and ~P) and branched stamens.", width = 320, height = 320 },
  { "cpfg/fig23.lua", nil, "Fig. 23",
    "A fern frond: polygonal leaflets traced by the turtle grow by one F per edge each step; "
    .. "the youngest are at the top.", width = 320, height = 320 },
  { "cpfg/fig24.lua", nil, "Fig. 24",
    "One polygon whose vertices (dots) are the ends of a branching framework, listed in "
    .. "order around the outline.", width = 320, height = 320 },
  { "cpfg/fig25.lua", nil, "Fig. 25",
    "Stacked polygons: three planar pieces of a bent blade, all opened in one branch and "
    .. "closed in another.", width = 320, height = 320 },
  { "cpfg/fig27.lua", "all", "Fig. 27",
    "Petals from one Bézier patch placed by the turtle (@PS, @PC, @PD): the parameter sets "
    .. "a–e of the guide's table, left to right.", width = 800, height = 300 },
  { "cpfg/fig28.lua", "all", "Fig. 28",
    "The development of a petal: values interpolated over 10 steps; after 0, 2, ..., 10 "
    .. "steps, left to right.", width = 800, height = 300 },
  { "cpfg/fig31.lua", "a", "Fig. 31a",
    "A chessboard texture per patch on a two-patch leaf surface: each patch gets the whole "
    .. "image.", width = 320, height = 320 },
  { "cpfg/fig31.lua", "b", "Fig. 31b",
    "The same texture per surface: laid over the surface's bounding box.",
    width = 320, height = 320 },
  { "cpfg/fig34.lua", "a", "Fig. 34a",
    "A texture on a polygon: the chessboard fills the polygon's bounding rectangle along "
    .. "the heading and the right vector.", width = 320, height = 320 },
  { "cpfg/fig33.lua", "a", "Fig. 33a",
    "A bark texture on a tapering stem of four cylinders; it continues from segment to "
    .. "segment.", width = 320, height = 320 },
  { "cpfg/fig33.lua", "b", "Fig. 33b",
    "The bark texture on a branching generalized cylinder; it is discontinuous at the forks, "
    .. "where two cylinders overlap.", width = 320, height = 320 },
  { "cpfg/fig34.lua", "b", "Fig. 34b",
    "A textured polygon: a venation image on a leaf blade.", width = 320, height = 320 },
  -- the figures of Anastacio et al. 2009, examples/sketch; plot = a sketch whose functions
  -- are plotted (lsys.sketch.plot) instead of a model drawn
  { "sketch/fig7.lua", "cone", "Fig. 7, pine cone",
    "A pine cone: Fibonacci phyllotaxis, 55 nodes per layer in an ovoid of eight thin "
    .. "layers; sketched woody scales point down at the base and up at the tip.",
    png = "sketch/fig7_cone.png", width = 320, height = 320 },
  { "sketch/fig7.lua", "flower", "Fig. 7, flower",
    "A flower head on a stalk: 13 nodes per layer in five close layers; long petals spread "
    .. "at the rim, shorter upright ones inside.", png = "sketch/fig7_flower.png",
    width = 320, height = 320 },
  { "sketch/fig8.lua", "decussate", "Fig. 8, decussate",
    "One sketch, three nodes per layer: pairs of leaves, each pair turned 90° from the last.",
    png = "sketch/fig8_decussate.png", width = 320, height = 320 },
  { "sketch/fig8.lua", "distichous", "Fig. 8, distichous",
    "The same sketch: pairs of leaves in one plane.", png = "sketch/fig8_distichous.png",
    width = 320, height = 320 },
  { "sketch/fig8.lua", "fibonacci", "Fig. 8, Fibonacci",
    "The same sketch: one leaf per node, 137.5° apart.", png = "sketch/fig8_fibonacci.png",
    width = 320, height = 320 },
  { "sketch/fig9.lua", "single", "Fig. 9, single compound leaf",
    "A pinnate leaf: distichous leaflets, two pairs per layer, shorter towards the tip.",
    png = "sketch/fig9_single.png", width = 320, height = 320 },
  { "sketch/fig9.lua", "double", "Fig. 9, double compound leaf",
    "The single leaf as the organ of a second, distichous sketch (composition, §7.2).",
    png = "sketch/fig9_double.png", width = 320, height = 320 },
  { "sketch/fig10.lua", "front", "Fig. 10, front",
    "A stem drawn with pen pressure, seen as it was drawn.", png = "sketch/fig10_front.png",
    width = 320, height = 320 },
  { "sketch/fig10.lua", "diagonal", "Fig. 10, diagonal",
    "The same plant from the diagonal: the stem leaves the drawing plane.",
    png = "sketch/fig10_diagonal.png", width = 320, height = 320 },
  { "sketch/fig10.lua", "side", "Fig. 10, side",
    "From the side: towards the viewer in its lower half, away at the top.",
    png = "sketch/fig10_side.png", width = 320, height = 320 },
  { "fig10_depth", nil, "Fig. 5, functions",
    "The functions of the pressure-drawn stem: internode, yaw, inclinations, sizes and "
    .. "pitch (panel 7).", png = "sketch/fig10_functions.png", plot = true,
    width = 320, height = 320 },
  { "sketch/fig11.lua", nil, "Fig. 11, bromeliad",
    "A bromeliad from two sketches on one stem, composed into one grammar: a rosette of "
    .. "long arching leaves and a stalk with red bracts.", png = "sketch/fig11.png",
    width = 320, height = 320 },
  { "fig11_leaves", nil, "Fig. 11, leaf functions",
    "The functions of the rosette's sketch.", png = "sketch/fig11_functions.png",
    plot = true, width = 320, height = 320 },
  { "sketch/fig12.lua", nil, "Fig. 12, bromeliad in 3D",
    "The same sketches with the stem drawn with pen pressure: the stalk leans away.",
    png = "sketch/fig12.png", width = 320, height = 320 },
  { "fig12_leaves", nil, "Fig. 12, leaf functions",
    "The functions of the pressure-drawn rosette: yaw in panel 2, pitch in panel 7.",
    png = "sketch/fig12_functions.png", plot = true, width = 320, height = 320 },
  { "sketch/fig13.lua", nil, "Fig. 13, foxglove",
    "A foxglove from a flower sketch and a leaf sketch on one stem: a raceme of hanging "
    .. "bells above a rosette of leaves.", png = "sketch/fig13.png", width = 320, height = 320 },
  { "sketch/fig14.lua", nil, "Fig. 14, foxglove in 3D",
    "The same with the stem drawn with pen pressure.", png = "sketch/fig14.png",
    width = 320, height = 320 },
  -- component graphs after Lintermann and Deussen 1999, examples/components
  { "components/fig2_abcd.lua", nil, "Fig. 2, A-B-C-D",
    "A stem (B) and a Hydra (C) of three twigs, each a Horn (D) linked to itself with "
    .. "recursion depth 3: nine instances of D, a bud on each.", width = 320, height = 320 },
  { "components/sunflower.lua", nil, "Fig. 4, sunflower",
    "Leaves on stalks as the branches of a Tree; at its top a Phiball of bracts, one of 34 "
    .. "petals and one of 500 seeds packed by the golden section.", width = 320, height = 320 },
  { "components/rhododendron.lua", nil, "Fig. 5, rhododendron",
    "20 twigs on a Phiball; each twig a Tree with flag lists: small twigs at 2 and 13, leaves "
    .. "elsewhere; trusses of flowers at the tips.", width = 320, height = 320 },
  { "components/fig6_ab.lua", "a", "Fig. 6a, chestnut: two Trees",
    "The chestnut's first stage: a trunk and its 12 branches, two Tree components with their "
    .. "number, spacing, angle and shape set.", png = "components/fig6a.png",
    width = 320, height = 320 },
  { "components/fig6_ab.lua", "b", "Fig. 6b, chestnut: four Trees",
    "Two more Trees, sub-branches and twigs: 96 and 576 of them, bare.",
    png = "components/fig6b.png", width = 320, height = 320 },
  { "components/chestnut.lua", nil, "Fig. 6c, chestnut",
    "A cascade of four Trees (trunk, branches, sub-branches, twigs) carrying 7,488 palmate "
    .. "leaves of 7 textured leaflets (52,416 Leaf instances); bark-textured stems.",
    width = 320, height = 320 },
  { "components/maple.lua", nil, "Fig. 7, maple",
    "Five levels of Trees from a short trunk: 1,260 twigs with 7,560 leaves in opposite "
    .. "pairs, each a Hydra of five pointed lobes on a petiole; a broad, rounded crown.",
    width = 320, height = 320 },
  { "components/agave.lua", nil, "Fig. 8, agave",
    "34 leaves on a Phiball whose length and bend are ranges over i plus a seeded random "
    .. "offset: the upright leaves are shorter and less bent.", width = 320, height = 320 },
  { "components/willow.lua", nil, "Fig. 9a, weeping willow",
    "336 long, thin twigs that a strong gravitropism turns straight down, with 8,064 narrow "
    .. "leaves.", width = 320, height = 320 },
  { "components/philodendron.lua", nil, "Fig. 9b, philodendron",
    "A World's cylinder guides the stem round a stick on a helix of radius 0.3 and pitch "
    .. "30°; heart-shaped leaves on petioles the stick does not pull, a Revo pot.",
    width = 320, height = 320 },
  { "components/fig10_ac.lua", "a", "Fig. 10a, pine undeformed",
    "The pine's graph without its Hyperpatch: a straight trunk, whorls of branches, 8,960 "
    .. "needles in pairs.", png = "components/fig10a.png", width = 320, height = 320 },
  { "components/pine.lua", nil, "Fig. 10b, pine",
    "A Hyperpatch bends the trunk and twigs; an isolating FFD above each needle pair keeps "
    .. "the needles undeformed.", width = 320, height = 320 },
  { "components/fig10_ac.lua", "c", "Fig. 10c, pine deformed whole",
    "The same bend without the isolating FFDs: the needles are deformed too, up to 1.7 "
    .. "times their size, most at the upper right.", png = "components/fig10c.png",
    width = 320, height = 320 },
  { "components/figC_tree.lua", nil, "Fig. C, a Tree's parameters",
    "One small Tree six times: as it is, gnarled, its branches crowded to the base, a "
    .. "range of branching angles, phototropic branches, a curved stem.",
    png = "components/figC.png", width = 640, height = 214 },
  { "components/figD_placement.lua", nil, "Fig. D, placement by multipliers",
    "A cone with a leaf at its base, multiplied by a Hydra (a star), a Wreath (a ring of "
    .. "candles) and a Phiball (the golden section on a sphere).",
    png = "components/figD.png", width = 640, height = 250 },
  -- incremental growth after Davison, examples/grow: a world grown to its length
  { "grow/davison.lua", nil, "Davison's five trees",
    "The paper's length, thickness and spawning rules (at most 256 limbs a tree before "
    .. "spawning, level < 10), young shoots browning with age, leaves on the upper twigs; "
    .. "60 ticks.",
    grow = true, png = "grow/davison.png", width = 480, height = 270 },
  { "grow/forest.lua", nil, "A forest of 20,000 limbs",
    "Five trees, a leader and a side branch at each fork rolled by the golden angle, grown "
    .. "80 ticks; `lsys grow examples/grow/forest.lua` grows it live in the window.",
    grow = true, png = "grow/forest.png", width = 480, height = 270 },
  { "grow/leafy.lua", nil, "Leaves as a surface",
    "One of Davison's trees whose leaves are the cpfg leaf surface (examples/cpfg/surfaces/"
    .. "leaf.s, 162 vertices a leaf) instead of quads, rewritten in place as they grow.",
    grow = true, png = "grow/leafy.png", width = 320, height = 320 },
  { "open/ulam.lua", nil, "Ulam's crystal",
    "An open L-system (Měch and Prusinkiewicz 1996, §5.1): each apex sends a sensor ahead, "
    .. "and the collision environment stops the ones that would meet another; 16 steps, "
    .. "the string cpfg derives with vlab's honda81.", png = "open/ulam.png",
    width = 320, height = 320 },
  { "open/shade.lua", nil, "Shoots that grow where the light is",
    "Every bud asks the light environment how much of an overcast sky it sees through the "
    .. "plant's own leaves: buds in light grow, in shade wait, in deep shade die; the crown "
    .. "fills the light and its inside stays bare.", png = "open/shade.png",
    width = 320, height = 320 },
  { "open/selforg.lua", nil, "A self-organizing tree",
    "Palubicki et al. 2009: buds sense their light in a shadow grid, the Borchert-Honda model "
    .. "shares the tree's vigour out among them, each grows a shoot as long as its share "
    .. "towards the light, and shaded branches are shed; 16 steps.", png = "open/selforg.png",
    width = 400, height = 400 },
  { "open/excurrent.lua", nil, "Apical control",
    "The same rules with more of the vigour kept by the main axis at each branching (the "
    .. "Borchert-Honda lambda 0.57 for 0.52) and a stronger pull upwards: a conical "
    .. "(excurrent) crown.", png = "open/excurrent.png", width = 400, height = 400 },
  { "open/wall.lua", nil, "Beside a wall",
    "The same tree 2.5 from a wall (seen edge on): the wall shades the buds near it in the "
    .. "grid, and the crown grows to the open side.", png = "open/wall.png",
    width = 400, height = 400 },
  { "open/neighbour.lua", nil, "Under a neighbour",
    "A sapling 3 from an older tree, its seed waiting 7 steps: in the older tree's shade it "
    .. "grows a fifth of what it grows alone, leaning out to the light.",
    png = "open/neighbour.png", scene = true, width = 480, height = 336 },
  { "open/forest.lua", nil, "A stand",
    "Nine trees grown together in one grid, seen from above, each with leaves of its own "
    .. "colour: each crown keeps to the space it wins (crown shyness); the edge trees spread "
    .. "out, an overtopped one stays small.", png = "open/forest.png", scene = true,
    width = 480, height = 336 },
}

--- The PNG name of picture p, under examples/gallery/.
function M.png (p)
  return p.png or
    p[1]:gsub("^abop/", ""):gsub("%.lua$", "") .. (p[2] and "_" .. p[2] or "") .. ".png"
end

local function load (examples, file, name)
  local v = dofile(examples .. "/" .. file)
  if name then v = v[name] end
  assert(v and v.derive, file .. ": no model " .. tostring(name))
  return v
end

--- Picture p (not a plot) at `size` (480: the ABOP pictures' side; the others scale with it),
-- its files under the folder `examples`: the scene, the lsys.render options the gallery
-- draws it with (no `out`: shaded as `lsys render` shades the same file) and what its
-- caption counts ({ n =, tris =, lines = }, or limbs or plants and tris).
function M.scene (p, size, examples)
  local w = math.floor((p.width or 480) * size / 480)
  local h = math.floor((p.height or 480) * size / 480)
  if p.grow then
    -- a grow file's world (lsys.grow), grown to its length
    local world = dofile(examples .. "/" .. p[1]).world():grow()
    local sc = world:scene()
    return sc, render.shaded(sc, { width = w, height = h }),
           { limbs = world:count(), tris = sc.ntriangles, lines = 0 }
  elseif p.scene then
    -- a file that returns the Scene it makes (a stand of open L-systems grown together)
    local sc = dofile(examples .. "/" .. p[1])
    return sc, render.shaded(sc, { width = w, height = h }),
           { plants = sc.ninstances, tris = sc.ntriangles, lines = 0 }
  end
  local m = load(examples, p[1], p[2])
  local s = m:derive()
  local sc = m:interpret(s, p[5])
  local ro = { width = w, height = h }
  for k, v in pairs(p.render or {}) do ro[k] = v end
  if not ro.wireframe then render.shaded(sc, ro) end   -- as `lsys render` shades it
  return sc, ro, { n = #s, tris = sc.ntriangles, lines = sc.nlines }
end

return M
