"""The contact: the normal force laws (:mod:`.laws`, the registry ``LAWS``) and the tangential models
(:mod:`.tangential`, the registry ``TANGENTIALS``), each one definition that declares its parameters and
what it can do."""
