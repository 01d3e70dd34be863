# ORBIT_FUZZ=ON: every target is compiled for libFuzzer's coverage feedback with AddressSanitizer
# and UndefinedBehaviorSanitizer (undefined behaviour aborts, so libFuzzer reports it as a
# crash), and fuzz/ builds libFuzzer binaries. libFuzzer is clang's: configure with
# -DCMAKE_CXX_COMPILER=clang++ (Debian 12: clang, libclang-rt-14-dev). scripts/fuzz.sh and
# scripts/test.sh do so in build-fuzz/.
if(NOT CMAKE_CXX_COMPILER_ID MATCHES "Clang")
  message(FATAL_ERROR "ORBIT_FUZZ needs clang (libFuzzer): configure with -DCMAKE_CXX_COMPILER=clang++")
endif()
add_compile_options(-fsanitize=fuzzer-no-link,address,undefined -fno-sanitize-recover=undefined
                    -fno-omit-frame-pointer)
add_link_options(-fsanitize=address,undefined)
