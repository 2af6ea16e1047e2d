# The shard scripts end to end: GNU parallel, and a one-node Slurm cluster
# started on this machine. Each installs what it lacks when it can (as root,
# with apt-get) and is skipped, with the reason, when it cannot run here.
add_test(NAME ShardsParallelScript
  COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/shards/parallel_test.sh $<TARGET_FILE:whisker> ${CMAKE_SOURCE_DIR})
add_test(NAME ShardsSlurmJobArray
  COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/shards/slurm_test.sh $<TARGET_FILE:whisker> ${CMAKE_SOURCE_DIR})
set_tests_properties(ShardsParallelScript ShardsSlurmJobArray PROPERTIES
  SKIP_RETURN_CODE 77 TIMEOUT 600 RESOURCE_LOCK apt LABELS cluster)
