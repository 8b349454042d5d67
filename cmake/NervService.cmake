# nerv_service(NAME): services/NAME/ holds the algorithm as a static library
# nerv_NAME (every .cpp but main.cpp, no LCM) and the thin service main.cpp,
# built as bin/NAME.
function(nerv_service name)
  file(GLOB algo_sources CONFIGURE_DEPENDS ${CMAKE_CURRENT_SOURCE_DIR}/*.cpp)
  list(REMOVE_ITEM algo_sources ${CMAKE_CURRENT_SOURCE_DIR}/main.cpp)
  if(NOT algo_sources)
    return()  # not written yet
  endif()
  add_library(nerv_${name} STATIC ${algo_sources})
  target_include_directories(nerv_${name} PUBLIC ${CMAKE_CURRENT_SOURCE_DIR})
  target_link_libraries(nerv_${name} PUBLIC nerv_common ${OpenCV_LIBS} Eigen3::Eigen Threads::Threads)
  if(EXISTS ${CMAKE_CURRENT_SOURCE_DIR}/main.cpp)
    add_executable(nerv_${name}_service main.cpp)
    set_target_properties(nerv_${name}_service PROPERTIES OUTPUT_NAME ${name}
                          RUNTIME_OUTPUT_DIRECTORY ${CMAKE_BINARY_DIR}/bin)
    target_link_libraries(nerv_${name}_service PRIVATE nerv_${name} nerv_transport nerv_build_version)
  endif()
endfunction()
