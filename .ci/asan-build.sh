# Sourced by .ci/sanitize and .ci/fuzz: configures build-asan/, the one clang build both use
# (IBLBAKE_FUZZ=ON: AddressSanitizer + UndefinedBehaviorSanitizer + libFuzzer coverage on every target;
# only the fuzz targets link libFuzzer's main, so the test executables run as usual).
cmake -S . -B build-asan -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_COMPILER=clang++ \
  -DIBLBAKE_FUZZ=ON -DIBLBAKE_BUILD_BENCHMARKS=OFF \
  "-DCMAKE_CXX_FLAGS_RELWITHDEBINFO=-O1 -gline-tables-only -DNDEBUG"
