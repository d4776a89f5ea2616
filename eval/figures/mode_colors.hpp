// One colour per mapper mode, the same in every run, every gnuplot figure and the report
// (a mode's colour never depends on which other modes ran or in what order). Standard
// and pruned take the seed's blue and red (Kretzschmar 2009, Figs. 6.1-6.5).
#pragma once

#include <string>

#include "render/palette.hpp"

namespace lifelong::eval {

/// The colour of a mode by name: fixed for the named modes (standard, pruned, pruned-exact,
/// pruned-naive, pruned-glc, pruned-nfr, pruned-overlap, pruned-dpg); POLICY+SPARSIFIER takes
/// its policy's colour (pruned's, pruned-overlap's or pruned-dpg's) darker or lighter by
/// sparsifier; any other name gets one of a fallback list chosen by a hash of the name
/// (FNV-1a), so it is stable across runs too.
render::Rgb ModeColour(const std::string& mode);

/// The same colour as "#rrggbb" (gnuplot `lc rgb`, HTML).
std::string ModeColourHex(const std::string& mode);

/// Any colour as "#rrggbb".
std::string HexColour(const render::Rgb& c);

}  // namespace lifelong::eval
