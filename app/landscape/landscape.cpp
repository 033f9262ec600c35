#include "app/landscape/landscape.h"
