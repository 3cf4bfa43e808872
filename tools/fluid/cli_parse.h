// Small parsers for the fluid subcommands' option values. Each throws
// std::invalid_argument with a message naming the option and what it expects.
#pragma once

#include <string>
#include <vector>

#include "fluid_solver.h"

namespace candela::fluid {

// "WxH", e.g. "128x128".
void parse_size(const std::string& option, const std::string& text, int& w, int& h);
// "x=0.5,y=0.05,rx=0.04,ry=0.03,rate=20000,temp=1900,flicker=0.3,hz=6"; keys
// may be left out (defaults from HeatSource).
HeatSource parse_source(const std::string& text);
// "T:S[,T:S...]" seconds:cells-per-second.
std::vector<WindKey> parse_wind(const std::string& text);
// The command line as one string, for manifests.
std::string join_command(int argc, char** argv);

}  // namespace candela::fluid
