#pragma once
// The scene effects implemented outside scene/ (by areas scene/ does not link), registered with
// scene's effect registry through its hook, register_effect() (scene/effect.hpp), as the VTK
// methods register with the method registry (vtk/vtk_integrators.hpp):
//   multiple_scattering   effects/multiple_scattering_effect.hpp (scattering/'s solvers)
// The CLI's main (cli/main.cpp) and the tests' main (tests/main.cpp) call
// register_standard_effects() first thing, so both see the same registry; a program that reads
// scenes through the library should do the same.
namespace rayint {

void register_standard_effects();  // idempotent

}  // namespace rayint
