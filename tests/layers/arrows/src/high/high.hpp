#pragma once  // a header-only library of the layer check's test project
