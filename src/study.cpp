// placeholder: the study runner
#include "oscidrum/study.hpp"
