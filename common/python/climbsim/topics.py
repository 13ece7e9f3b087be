"""Topic names of climbsim: `NAME = "group/Type"` per topic and TOPICS, the rows of the topic
table (name, IDL type, producer, rate, QoS profile).

The one list is common/include/climbsim/topic_catalog.hpp; the build generates
<build>/python/climbsim_topics.py from it (climbsim-topicgen), which the wrappers in <build>/bin
put on the path. This module only re-exports it, so that the names cannot drift apart.
"""

from climbsim_topics import *  # noqa: F401,F403  (generated: the names are the table's)
from climbsim_topics import TOPICS  # noqa: F401
