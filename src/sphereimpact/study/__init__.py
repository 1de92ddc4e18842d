"""The replication study: configured cases, run files, tables, the published-value report, notebooks.

This layer reads and writes files (pandas, YAML); the physics below it does not.
"""
