// placeholder: the engine
#include "oscidrum/simulate.hpp"
