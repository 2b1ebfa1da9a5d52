// placeholder: implemented by the metrics work
#include "oscidrum/metrics.hpp"
