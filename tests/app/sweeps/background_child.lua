-- One point of a protocol (background_child_protocol.lua) that leaves a child process holding
-- its standard output: tests/app/sweep_job_background_child.sh.
return { protocol = "background_child_protocol.lua", product = { n = { 1 } } }
