// The virtual-test tables of a scene file: [tensile], [compression], [softness] (a table
// present means the test runs after the pipeline's stages). Keys name their unit; every key,
// its default and its accepted range are listed in docs/virtual-tests.md. Errors are
// InputError messages naming the file, the dotted key and the accepted range, as for the
// rest of the scene (scene.h).
#pragma once

#include <string>
#include <vector>

#include "campaigns/table_reader.h"
#include "engine/pipeline/virtual_tests.h"

namespace fibrenet::campaigns {

// The root keys this reader owns.
const std::vector<std::string>& SceneTestTables();

// Reads the test tables present under `root` into `tests`.
void ReadSceneTests(TableReader& root, ReadContext& ctx, pipeline::VirtualTestsSpec& tests);

}  // namespace fibrenet::campaigns
