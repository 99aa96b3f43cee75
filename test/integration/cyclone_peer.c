/* An outside DDS peer on Eclipse Cyclone DDS, for the security test only (never part of
 * the product): it joins a domain with no security, writes a goal on mission/goal every
 * 0.1 s, and after SECONDS prints what it found of the others, on one line:
 *
 *   cyclone peer: goals=N matched_readers=M participants=P topics=a,b,...
 *
 * usage: stickrep-cyclone-peer DOMAIN SECONDS TARGET
 * Exit code 0, or 2 for a bad command line, 1 if Cyclone DDS fails. */
#include <dds/dds.h>

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "mission.h"

#define MAX_TOPICS 64

static int GuidsEqual(const dds_guid_t* a, const dds_guid_t* b) {
  return memcmp(a->v, b->v, sizeof(a->v)) == 0;
}

/* Same participant: the first 12 bytes of a GUID are its participant's prefix. */
static int SamePrefix(const dds_guid_t* a, const dds_guid_t* b) {
  return memcmp(a->v, b->v, 12) == 0;
}

typedef struct {
  char* names[MAX_TOPICS];
  int count;
} TopicSet;

static void AddTopic(TopicSet* set, const char* name) {
  for (int i = 0; i < set->count; ++i) {
    if (strcmp(set->names[i], name) == 0) return;
  }
  if (set->count < MAX_TOPICS) set->names[set->count++] = strdup(name);
}

/* Takes every endpoint sample of a built-in reader; remote ones add their topic. */
static void TakeEndpoints(dds_entity_t reader, const dds_guid_t* own, TopicSet* topics) {
  void* samples[16] = {0};
  dds_sample_info_t infos[16];
  for (;;) {
    const int n = dds_take(reader, samples, infos, 16, 16);
    if (n <= 0) break;
    for (int i = 0; i < n; ++i) {
      const dds_builtintopic_endpoint_t* e = samples[i];
      if (infos[i].valid_data && !SamePrefix(&e->participant_key, own)) {
        AddTopic(topics, e->topic_name);
      }
    }
    dds_return_loan(reader, samples, n);
  }
}

/* Takes every participant sample; counts the remote ones seen alive. */
static void TakeParticipants(dds_entity_t reader, const dds_guid_t* own, dds_guid_t* seen,
                             int* count) {
  void* samples[16] = {0};
  dds_sample_info_t infos[16];
  for (;;) {
    const int n = dds_take(reader, samples, infos, 16, 16);
    if (n <= 0) break;
    for (int i = 0; i < n; ++i) {
      const dds_builtintopic_participant_t* p = samples[i];
      if (!infos[i].valid_data || SamePrefix(&p->key, own)) continue;
      int known = 0;
      for (int j = 0; j < *count; ++j) known |= GuidsEqual(&seen[j], &p->key);
      if (!known && *count < MAX_TOPICS) seen[(*count)++] = p->key;
    }
    dds_return_loan(reader, samples, n);
  }
}

int main(int argc, char** argv) {
  if (argc != 4) {
    fprintf(stderr, "usage: %s DOMAIN SECONDS TARGET\n", argv[0]);
    return 2;
  }
  const int domain = atoi(argv[1]);
  const double seconds = atof(argv[2]);
  const dds_entity_t participant = dds_create_participant((dds_domainid_t)domain, NULL, NULL);
  if (participant < 0) {
    fprintf(stderr, "cyclone peer: %s\n", dds_strretcode(-participant));
    return 1;
  }
  dds_guid_t own;
  dds_get_guid(participant, &own);
  const dds_entity_t topic = dds_create_topic(participant, &stickrep_msgs_MissionGoal_desc,
                                              "mission/goal", NULL, NULL);
  dds_qos_t* qos = dds_create_qos();
  dds_qset_reliability(qos, DDS_RELIABILITY_RELIABLE, DDS_SECS(1));
  dds_qset_history(qos, DDS_HISTORY_KEEP_LAST, 10);
  const dds_entity_t writer = dds_create_writer(participant, topic, qos, NULL);
  dds_delete_qos(qos);
  const dds_entity_t publications =
      dds_create_reader(participant, DDS_BUILTIN_TOPIC_DCPSPUBLICATION, NULL, NULL);
  const dds_entity_t subscriptions =
      dds_create_reader(participant, DDS_BUILTIN_TOPIC_DCPSSUBSCRIPTION, NULL, NULL);
  const dds_entity_t participants =
      dds_create_reader(participant, DDS_BUILTIN_TOPIC_DCPSPARTICIPANT, NULL, NULL);
  if (topic < 0 || writer < 0 || publications < 0 || subscriptions < 0 || participants < 0) {
    fprintf(stderr, "cyclone peer: could not create its topic, writer or readers\n");
    dds_delete(participant);
    return 1;
  }
  TopicSet topics = {{0}, 0};
  dds_guid_t seen[MAX_TOPICS];
  int participant_count = 0;
  int goals = 0;
  stickrep_msgs_MissionGoal goal;
  memset(&goal, 0, sizeof(goal));
  goal.goal_id = "cyclone";
  goal.target = argv[3];
  const dds_time_t until = dds_time() + (dds_duration_t)(seconds * 1e9);
  while (dds_time() < until) {
    goal.header.stamp_ns = dds_time();
    goal.header.sequence_number = (uint32_t)(goals + 1);
    if (dds_write(writer, &goal) == DDS_RETCODE_OK) goals++;
    TakeEndpoints(publications, &own, &topics);
    TakeEndpoints(subscriptions, &own, &topics);
    TakeParticipants(participants, &own, seen, &participant_count);
    dds_sleepfor(DDS_MSECS(100));
  }
  dds_publication_matched_status_t matched;
  dds_get_publication_matched_status(writer, &matched);
  printf("cyclone peer: goals=%d matched_readers=%u participants=%d topics=", goals,
         matched.total_count, participant_count);
  for (int i = 0; i < topics.count; ++i) printf("%s%s", i ? "," : "", topics.names[i]);
  printf("\n");
  for (int i = 0; i < topics.count; ++i) free(topics.names[i]);
  dds_delete(participant);
  return 0;
}
